"""A step of scripts/bench_speed8.sh (its arguments as there: sys.argv[1:])."""
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
out = ["## ECP5 speed grade 8: every model at its deepest pipeline", "",
       "`scripts/bench_speed8.sh` (SEEDS=%s): `specgen synth --target ecp5 --speed 8 --dsp`, LFE5U-25F grade 8; Fmax the median" % sys.argv[2],
       "(range) over nextpnr-ecp5 seeds, never above a block's limit at grade 8 (DP16KD clock pulse ≥ 1.842 ns: 271.4 MHz;",
       "MULT18X18D input register to P 3.045 ns: 328.4 MHz; prjtrellis-db `ECP5/timing/speed_8/cells.json`).", "",
       "| model | stages | LUT4 | MULT18X18D | DP16KD | Fmax MHz | nextpnr's own, median (range) |", "|---|---|---|---|---|---|---|"]
for r in rows:
    s = r["seeds"]
    route = "%.1f (%.1f–%.1f)" % (r["route"], min(s), max(s)) if s and r["route"] else "–"
    lim = " (%s limit)" % r["by"].split()[0] if r["by"] else ""
    out.append("| %s | %s | %s | %s | %s | %.1f%s | %s |" % (r["model"], r["stages"], r["lut"], r["dsp"], r["bram"], r["fmax"], lim, route))
text = open("benchmarks/hw.md").read()
section = "\n".join(out) + "\n"
start = text.find("## ECP5 speed grade 8")
if start < 0:
    at = text.find("## The models compared at the operating point")
    text = text[:at] + section + "\n" + text[at:]
else:
    end = text.find("\n## ", start + 1)
    text = text[:start] + section + ("" if end < 0 else text[end + 1:])
open("benchmarks/hw.md", "w").write(text)
print(section)
