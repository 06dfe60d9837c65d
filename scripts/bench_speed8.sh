#!/usr/bin/env bash
# Every model at its deepest ECP5 pipeline on the fastest part, LFE5U-25F speed grade 8
# (`synth --target ecp5 --speed 8`: nextpnr-ecp5 places for grade 8, and the blocks' limits are
# read at grade 8 — a DP16KD's clock pulse allows 271.4 MHz there). Fmax over nextpnr seeds
# 1..$SEEDS (median, range), never above a block's limit. The delay model of --target-mhz is
# calibrated on grade 6, so the depth is each model's deepest (`--stages` at its maximum).
# Rewrites the "ECP5 speed grade 8" section of benchmarks/hw.md.
#   SEEDS=5 scripts/bench_speed8.sh
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
# every model the generator has but blinn-pow (73 DSP blocks: it fits neither part)
for model in $(models); do
    [ "$model" = blinn-pow ] && continue
    dir="$work/$model"
    stages=$(max_stages --model "$model" --target ecp5)
    $bin generate --out "$dir" --model "$model" --target ecp5 --stages "$stages" >/dev/null 2>&1
    $bin synth --rtl "$dir" --target ecp5 --speed 8 --dsp --seeds "$seeds" --json "$work/$model.json" > "$work/$model.log" 2>&1 || { cat "$work/$model.log" >&2; exit 1; }
    MODEL=$model STAGES=$stages python3 - "$work/$model.json" >> "$rows" <<'PY'
import json, os, sys
d = json.load(open(sys.argv[1]))
print(json.dumps(dict(model=os.environ["MODEL"], stages=int(os.environ["STAGES"]), fmax=d.get("fmax_mhz"), route=d.get("fmax_route_mhz"),
                      by=d.get("fmax_limited_by"), seeds=d.get("fmax_seeds") or [], lut=d.get("luts"), dsp=d.get("dsp_blocks"), bram=d.get("block_rams"))))
PY
done
python3 - "$rows" "$seeds" <<'PY'
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
PY
