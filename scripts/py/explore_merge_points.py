"""A step of scripts/bench_explore.sh (its arguments as there: sys.argv[1:])."""
import json, sys
e = json.load(open(sys.argv[1]))
e["points"] = [p for p in e["points"] if p["measured"]]
seen = {p["id"] for p in e["points"]}
for p in json.load(open(sys.argv[2]))["points"]:
    if p["measured"] and p["id"] not in seen:
        e["points"].append(p)
print(json.dumps(e, indent=1))
