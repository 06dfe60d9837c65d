"""A step of scripts/bench_two_units.sh (its arguments as there: sys.argv[1:])."""
import statistics, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
verify = open(sys.argv[2]).read().strip().splitlines()
seeds = sys.argv[3]
unreg = sorted(set(l.strip() for l in open(sys.argv[4]) if l.strip()))
units = [u.split(":") for u in sys.argv[5:]]
print("# Two units in one iCE40 UP5K")
print()
print("`scripts/bench_two_units.sh` (SEEDS=%s): two units of different models, each generated with a" % seeds)
print("`--dsp-budget`, in two tops: `pair_top`, serial I/O (every port of both units from or to a")
print("flip-flop of a shift chain, the units reading the input chain and the output chain loading their")
print("outputs, with no holding registers between), and `pair_plain_top`, a top of one's own (both units fed and read by")
print("plain registers, no serial wrapper: [`tb/pair_plain_top.v`](../tb/pair_plain_top.v)).")
print("`synth_ice40 -dsp` on the toolchains the table's yosys column names (`CHAINS`: Debian 12's yosys 0.23 with")
print("nextpnr-ice40 0.4, YoWASP's 0.70 with its nextpnr-ice40), `nextpnr-ice40 --up5k --package sg48 --freq 100`")
print("over seeds 1..%s." % seeds)
print("Fmax is nextpnr's, after routing; nextpnr-ice40 does not time the multiply inside an SB_MAC16")
print("(IceStorm's data: 153.7 MHz with its registers). A block without its output register (`specgen")
print("synth` lists them under `unregistered`, below) is not timed at all, so with one the figure is an")
print("upper bound.")
print()
print("| unit | model | --dsp-budget | --stages |")
print("|---|---|---|---|")
for top, model, budget, stages in units:
    print(f"| `{top}` | {model} | {budget} | {stages} |")
print()
print("| top | yosys | Fmax MHz, median (range) | per seed | logic cells (ICESTORM_LC) | SB_MAC16 |")
print("|---|---|---|---|---|---|")
versions = list(dict.fromkeys(r[1] for r in rows))
for kind, name in (("serial", "`pair_top` (serial I/O)"), ("plain", "`pair_plain_top` (plain registers)")):
    for v in versions:
        every = [r for r in rows if r[0] == kind and r[1] == v]
        rs = [r for r in every if r[3] != "unplaced"]
        unplaced = [r[2] for r in every if r[3] == "unplaced"]
        per = ", ".join(f"{r[2]}: {float(r[3]):.1f}" if r[3] != "unplaced" else f"{r[2]}: does not place" for r in every)
        if not rs:
            print(f"| {name} | {v.replace('_', ' ')} | no seed places | {per} | | |")
            continue
        mhz = [float(r[3]) for r in rs]
        fig = f"{statistics.median(mhz):.1f} ({min(mhz):.1f}–{max(mhz):.1f})"
        if unplaced:
            fig += f" over the {len(rs)} seeds that place"
        print(f"| {name} | {v.replace('_', ' ')} | {fig} | {per} | {rs[0][4]} of {rs[0][5]} | {rs[0][6]} of {rs[0][7]} |")
print()
print("Each unit's own netlist with each yosys (`specgen synth --dsp --verify --verify-exhaustive`: every")
print("(cos_g, n) through the netlist under Verilator, against the golden model):")
print()
for v in verify:
    print(f"- {v}")
print()
print("SB_MAC16 without an output register (each unit's `specgen synth`):")
print()
for u in unreg:
    print(f"- {u}")
