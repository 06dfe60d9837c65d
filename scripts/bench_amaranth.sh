#!/usr/bin/env bash
# Regenerates benchmarks/amaranth.md: a generated unit built into an iCEBreaker (UP5K)
# bitstream through Amaranth's own platform (amaranth-boards' ICEBreakerPlatform, the unit's
# Amaranth component inside tb/python/icebreaker_top.py), beside `specgen synth` of the same
# unit: logic cells and Fmax, the median (range) over nextpnr seeds 1..SEEDS (default 20: a seed moves either flow by 6 %, so five seeds left the two medians apart by chance), both
# asked for the same clock. STAGES (default 12) and MHZ (default 100) choose the unit.
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-20}; stages=${STAGES:-12}; mhz=${MHZ:-100}
unit="$work/unit"
$bin generate --stages "$stages" --clock-mhz "$mhz" --out "$unit" >/dev/null
$bin synth --rtl "$unit" --dsp --seeds "$seeds" --json "$work/synth.json" >/dev/null
for s in $(seq 1 "$seeds"); do
    python3 tb/python/icebreaker_top.py "$unit" "$work/build$s" "$mhz" "$s" >/dev/null
done
python3 scripts/py/amaranth_table.py "$work" "$seeds" "$stages" "$mhz" > benchmarks/amaranth.md
bench_stamp "scripts/bench_amaranth.sh" >> benchmarks/amaranth.md
echo "wrote benchmarks/amaranth.md" >&2
