#!/usr/bin/env python3
"""Merges explorations' calibration rows into the delay model's data.

    scripts/merge_calibration.py [--keep] OUT NEW.csv...

Each NEW is an exploration's calibration.csv (`specgen explore --results` writes it: family,
datapath, stages, the plan's slowest and mean stretch, nextpnr's median over the seeds and each
seed's, the generate flags beyond the defaults). A row of NEW replaces OUT's row of the same unit
(family, datapath, stages, flags); with --keep, OUT's row stays and NEW only adds units OUT lacks
(the explorations' fronts, measured at widths between the calibration's, join the grid without
changing a unit it already has). OUT is written sorted, so the file's diff shows the rows that
came in.
"""
import csv
import sys

FIELDS = ["family", "model", "stages", "stage_delay_estimate", "stage_delay_mean", "fmax_mhz", "fmax_seeds", "args", "rtl_sha256"]


def key(r):
    return (r["family"], r["model"], r["stages"], " ".join(r["args"].split()))


def main():
    argv = sys.argv[1:]
    keep = "--keep" in argv
    argv = [a for a in argv if a != "--keep"]
    if len(argv) < 1:
        sys.exit(__doc__)
    out, new = argv[0], argv[1:]
    with open(out) as f:
        rows = {key(r): r for r in csv.DictReader(f)}
    added = 0
    for name in new:
        with open(name) as f:
            for r in csv.DictReader(f):
                if keep and key(r) in rows:
                    continue
                added += key(r) not in rows
                rows[key(r)] = r
    with open(out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS, lineterminator="\n")
        w.writeheader()
        for k in sorted(rows, key=lambda k: (k[0], k[1], k[3], int(k[2]))):
            w.writerow({f: rows[k].get(f) or "" for f in FIELDS})
    print(f"{out}: {added} unit(s) added, {len(rows)} in all", file=sys.stderr)


if __name__ == "__main__":
    main()
