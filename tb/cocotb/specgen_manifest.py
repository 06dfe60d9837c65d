"""Helpers for the cocotb testbench that need no simulator.

    specgen_manifest.py RTL_DIR KEY        print a field of the unit's manifest (e.g. top)
    specgen_manifest.py --check RTL_DIR [VECTORS]
                                           exit 1 naming the first difference unless the
                                           directory holds what specgen wrote (each listed
                                           file's SHA-256, the unit's header fingerprint) and
                                           the vectors were written for the same configuration
    specgen_manifest.py --check-results F  exit 1 unless the cocotb results file F exists,
                                           has a test, and has no failure or error
"""
import glob
import hashlib
import json
import os
import sys
import xml.etree.ElementTree as ET


def manifest(rtl_dir):
    """The specgen manifest (<top>.json with "generator": "specgen") in rtl_dir."""
    found = []
    for path in sorted(glob.glob(os.path.join(rtl_dir, "*.json"))):
        with open(path) as f:
            try:
                data = json.load(f)
            except ValueError:
                continue
        if isinstance(data, dict) and data.get("generator") == "specgen":
            found.append(data)
    if len(found) != 1:
        raise SystemExit(f"expected one specgen manifest in {rtl_dir}, found {len(found)}")
    return found[0]


def header_fingerprint(path, prefix):
    """The fingerprint a generated file states in its first lines (None when it states none)."""
    with open(path, errors="replace") as f:
        for _, line in zip(range(40), f):
            line = line.strip()
            for lead in ("//", "#"):
                if line.startswith(lead) and line[len(lead):].strip().startswith(prefix):
                    return line[len(lead):].strip()[len(prefix):].split()[0]
    return None


def check(rtl_dir, vectors=None):
    """Raises SystemExit naming the first file that is not what specgen wrote for the manifest."""
    info = manifest(rtl_dir)
    for entry in info.get("files", []):
        path = os.path.join(rtl_dir, entry["name"])
        if os.path.isfile(path):
            with open(path, "rb") as f:
                got = hashlib.sha256(f.read()).hexdigest()
            if got != entry["sha256"]:
                raise SystemExit(f"{path} is not the file specgen wrote (its SHA-256 is not the manifest's): regenerate it")
    fingerprint = info.get("fingerprint")
    if fingerprint is None:
        return info
    unit = os.path.join(rtl_dir, info["top"] + ".v")
    stated = header_fingerprint(unit, "Fingerprint:")
    if stated is not None and stated != fingerprint:
        raise SystemExit(f"{unit} was generated for another configuration (fingerprint {stated}) than its manifest ({fingerprint})")
    if vectors is not None:
        stated = header_fingerprint(vectors, "Fingerprint:")
        if stated is not None and stated != fingerprint:
            raise SystemExit(f"{vectors} holds vectors of another configuration (fingerprint {stated}) than the unit in {rtl_dir} ({fingerprint}): write them with `specgen vectors --rtl {rtl_dir}`")
    return info


def check_results(path):
    if not os.path.exists(path):
        raise SystemExit(f"FAIL: no cocotb results file {path}: the simulation did not run")
    root = ET.parse(path).getroot()
    cases = root.findall(".//testcase")
    bad = [c.get("name") for c in cases if c.find("failure") is not None or c.find("error") is not None]
    if not cases:
        raise SystemExit(f"FAIL: {path} records no test")
    if bad:
        raise SystemExit(f"FAIL: {len(bad)} of {len(cases)} cocotb tests failed: {', '.join(bad)}")
    print(f"PASS: {len(cases)} cocotb test(s) in {path}")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--check-results":
        check_results(sys.argv[2])
    elif len(sys.argv) in (3, 4) and sys.argv[1] == "--check":
        check(sys.argv[2], sys.argv[3] if len(sys.argv) == 4 else None)
        print(f"PASS: {sys.argv[2]} holds what specgen wrote")
    elif len(sys.argv) == 3:
        print(manifest(sys.argv[1])[sys.argv[2]])
    else:
        raise SystemExit(__doc__)
