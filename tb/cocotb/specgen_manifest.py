"""Helpers for the cocotb testbench that need no simulator.

    specgen_manifest.py RTL_DIR KEY        print a field of the unit's manifest (e.g. top)
    specgen_manifest.py --check-results F  exit 1 unless the cocotb results file F exists,
                                           has a test, and has no failure or error
"""
import glob
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
    elif len(sys.argv) == 3:
        print(manifest(sys.argv[1])[sys.argv[2]])
    else:
        raise SystemExit(__doc__)
