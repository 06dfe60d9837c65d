"""A step of scripts/bench_speed8.sh (its arguments as there: sys.argv[1:])."""
import json, os, sys
d = json.load(open(sys.argv[1]))
print(json.dumps(dict(model=os.environ["MODEL"], stages=int(os.environ["STAGES"]), fmax=d.get("fmax_mhz"), route=d.get("fmax_route_mhz"),
                      by=d.get("fmax_limited_by"), seeds=d.get("fmax_seeds") or [], lut=d.get("luts"), dsp=d.get("dsp_blocks"), bram=d.get("block_rams"))))
