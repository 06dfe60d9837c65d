"""A step of scripts/calibration_age.sh (its arguments as there: sys.argv[1:])."""
import collections, csv, sys
families, models, every = sys.argv[1].split(), sys.argv[2].split(), sys.argv[3] == "1"
rows = collections.defaultdict(list)
for r in csv.DictReader(open("data/delay_calibration.csv")):
    if r["family"] in families and (not models or r["model"] in models) and not r["args"].strip() and r["fmax_seeds"].split():
        rows[(r["family"], r["model"])].append((int(r["stages"]), r["fmax_seeds"].split()[0]))
for (family, model), units in sorted(rows.items()):
    units.sort()
    pick = units if every else sorted({units[0], units[len(units) // 2], units[-1]})
    for stages, seed1 in pick:
        print(family, model, stages, seed1)
