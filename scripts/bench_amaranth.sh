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
python3 - "$work" "$seeds" "$stages" "$mhz" > benchmarks/amaranth.md <<'PY'
import json, re, statistics, sys
work, seeds, stages, mhz = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
synth = json.load(open(f"{work}/synth.json"))
fmax, cells = [], None
for s in range(1, seeds + 1):
    log = open(f"{work}/build{s}/top.tim").read()
    fmax.append(float(re.findall(r"Max frequency for clock 'clk': ([0-9.]+) MHz", log)[-1]))
    cells = cells or int(re.search(r"ICESTORM_LC:\s+(\d+)/", log).group(1))
med = statistics.median(fmax)
print("# The unit through Amaranth's own build\n")
print(f"`specgen generate --stages {stages}` (the default quadratic unit), its Amaranth component inside a")
print("user's top on the iCEBreaker (tb/python/icebreaker_top.py: an LFSR feeding the unit, the results")
print("folded in registered steps onto an LED, the clock pin constrained at the unit's clock), built by")
print("`ICEBreakerPlatform().build(..., synth_opts=\"-dsp\")` to a bitstream; beside `specgen synth --dsp` of")
print(f"the same unit (its serial I/O wrapper). Both asked for {mhz} MHz, nextpnr seeds 1..{seeds}.\n")
print("| flow | logic cells | Fmax MHz, median (range) |")
print("|---|---|---|")
print(f"| `specgen synth --dsp` | {synth['logic_cells']} | {synth['fmax_route_mhz']:.1f} ({min(synth['fmax_seeds']):.1f}-{max(synth['fmax_seeds']):.1f}) |")
print(f"| Amaranth, iCEBreaker bitstream | {cells} | {med:.1f} ({min(fmax):.1f}-{max(fmax):.1f}) |")
print(f"\nThe Amaranth build reaches {100 * med / synth['fmax_route_mhz']:.1f} % of `synth`'s median; its cells include the")
print("top's LFSR and fold, not the serial wrapper's shift registers.\n")
PY
bench_stamp "scripts/bench_amaranth.sh" >> benchmarks/amaranth.md
echo "wrote benchmarks/amaranth.md" >&2
