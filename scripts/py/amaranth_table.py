"""A step of scripts/bench_amaranth.sh (its arguments as there: sys.argv[1:])."""
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
