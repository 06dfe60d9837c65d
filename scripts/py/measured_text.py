"""A step of scripts/bench_common.sh (its arguments as there: sys.argv[1:])."""
import json, statistics, sys
m = json.load(open(sys.argv[1])).get("measured") or {}
capped, route = m.get("fmax_seeds") or [], m.get("route_seeds") or []
if m.get("fmax_mhz") is None or not capped:
    print("-")
elif not route or max(route) <= max(capped):
    print("%.1f (%.1f-%.1f)" % (m["fmax_mhz"], min(capped), max(capped)))
else:
    print("%.1f (%.1f-%.1f; %s limit; nextpnr %.1f, %.1f-%.1f)" % (m["fmax_mhz"], min(capped), max(capped), (m.get("limited_by") or "block").split()[0], statistics.median(route), min(route), max(route)))
