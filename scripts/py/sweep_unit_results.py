"""A step of scripts/bench_common.sh (its arguments as there: sys.argv[1:])."""
import glob, json, shutil, sys
plan, mode = sys.argv[1], sys.argv[2]
points = json.load(open(plan + "/points.json"))["points"]
for d in sys.argv[3:]:
    manifest = next(m for m in (json.load(open(f)) for f in sorted(glob.glob(d + "/*.json"))) if m.get("generator") == "specgen")
    [p] = [p for p in points if p["id"].endswith("-" + manifest["fingerprint"][:8]) and p["params"]["stages"] == manifest["stages"]]
    json.dump(p, open(f"{d}.{mode}.measured.json", "w"), indent=1)
    shutil.copyfile(f"{plan}/synth/{p['id']}.json", f"{d}.{mode}.json")
