#!/usr/bin/env bash
# Two units of different models in one iCE40 UP5K (issue 49): each generated with a
# --dsp-budget so that their SB_MAC16s together fit the device's 8, both instantiated in one
# top (a serial-I/O wrapper as `synth` uses: every port of both units from or to a flip-flop),
# synthesized by yosys (synth_ice40 -dsp) and placed and routed by nextpnr-ice40 over seeds
# 1..$SEEDS (median and range of the clock, the device's logic cells and DSPs). Each unit's
# own netlist is then checked against its golden model, every (cos_g, n) input, by
# `specgen synth --verify --verify-exhaustive` (yosys's cell models, Verilator).
# Writes benchmarks/two-units.md.
#   SEEDS=5 A=quadratic:3:28 B=blinn:5:47 scripts/bench_two_units.sh
# A and B: model:dsp-budget:stages.
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
A=${A:-quadratic:3:28}
B=${B:-blinn:5:47}
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
# the top: both units behind one serial chain in and one out (each port from or to a register)
python3 - "$work" "${units[@]}" > "$run/pair_top.v" <<'PY'
import json, sys
work, units = sys.argv[1], [u.split(":") for u in sys.argv[2:]]
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
print(f"""// two specgen units in one device, serial I/O (scripts/bench_two_units.sh); not for a design
module pair_top (input wire clk, input wire sin, input wire load, output wire sout);
    reg  [{ins - 1}:0] in_chain;
    reg  [{ins - 1}:0] in_reg;
    reg  [{outs - 1}:0] out_reg;
    reg  [{outs - 1}:0] out_chain;
    wire [{outs - 1}:0] unit_out;
    always @(posedge clk) begin
        in_chain <= {{in_chain[{ins - 2}:0], sin}};
        if (load) in_reg <= in_chain;
        out_reg <= unit_out;
        if (load) out_chain <= out_reg;
        else      out_chain <= {{out_chain[{outs - 2}:0], 1'b0}};
    end
    assign sout = out_chain[{outs - 1}];
{chr(10).join(inst)}
endmodule""")
PY
( cd "$run" && yosys -q -l yosys.log -p "read_verilog $(ls *.v | tr '\n' ' '); synth_ice40 -dsp -top pair_top -json pair.json; tee -o stat.txt stat" ) \
    || { tail -20 "$run/yosys.log" >&2; exit 1; }
rows="$work/rows.txt"; : > "$rows"
for seed in $(seq 1 "$seeds"); do
    ( cd "$run" && nextpnr-ice40 --up5k --package sg48 --pcf-allow-unconstrained --timing-allow-fail --json pair.json --freq 100 --seed "$seed" > "pnr$seed.log" 2>&1 ) \
        || { grep ERROR "$run/pnr$seed.log" >&2; tail -5 "$run/pnr$seed.log" >&2; exit 1; }
    mhz=$(grep "Max frequency for clock" "$run/pnr$seed.log" | tail -1 | sed -n 's/.*: \([0-9.]*\) MHz.*/\1/p')
    lc=$(grep -m1 "ICESTORM_LC:" "$run/pnr$seed.log" | sed -n 's/.*ICESTORM_LC: *\([0-9]*\)\/ *\([0-9]*\).*/\1 \2/p')
    dsp=$(grep -m1 "ICESTORM_DSP:" "$run/pnr$seed.log" | sed -n 's/.*ICESTORM_DSP: *\([0-9]*\)\/ *\([0-9]*\).*/\1 \2/p')
    echo "$seed $mhz $lc $dsp" >> "$rows"
done
# each unit's own netlist, every input, against its golden model
verify="$work/verify.txt"; : > "$verify"; : > "$work/unregistered.txt"
for u in "${units[@]}"; do
    top=${u%%:*}
    $bin synth --rtl "$work/$top" --dsp --no-pnr --verify --verify-exhaustive > "$work/$top.verify.log" 2>&1 \
        || { cat "$work/$top.verify.log" >&2; exit 1; }
    echo "$top: $(grep -i -m2 'verify\|netlist' "$work/$top.verify.log" | tr '\n' ' ')" >> "$verify"
    grep "unregistered" "$work/$top.verify.log" | sed "s/^ *unregistered *//; s/^/$top: /" >> "$work/unregistered.txt" || true
done
python3 - "$rows" "$verify" "$seeds" "$run/stat.txt" "$work/unregistered.txt" "${units[@]}" > benchmarks/two-units.md <<'PY'
import statistics, sys, re
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
verify = open(sys.argv[2]).read().strip().splitlines()
seeds, stat = sys.argv[3], open(sys.argv[4]).read()
unreg = sorted(set(l.strip() for l in open(sys.argv[5]) if l.strip()))
units = [u.split(":") for u in sys.argv[6:]]
mhz = [float(r[1]) for r in rows]
mac = re.findall(r"SB_MAC16\s+(\d+)", stat)
print("# Two units in one iCE40 UP5K")
print()
print("`scripts/bench_two_units.sh` (SEEDS=%s): two units of different models, each generated with a" % seeds)
print("`--dsp-budget`, in one top (`pair_top`, serial I/O: every port of both units from or to a")
print("flip-flop), `yosys synth_ice40 -dsp`, `nextpnr-ice40 --up5k --package sg48 --freq 100` over seeds")
print("1..%s. Fmax is nextpnr's, after routing; nextpnr-ice40 does not time the multiply inside an" % seeds)
print("SB_MAC16 (IceStorm's data: 153.7 MHz with its registers). A block without its output register")
print("(`specgen synth` lists them under `unregistered`, below) is not timed at all, so with one the")
print("figure is an upper bound.")
print()
print("| unit | model | --dsp-budget | --stages |")
print("|---|---|---|---|")
for top, model, budget, stages in units:
    print(f"| `{top}` | {model} | {budget} | {stages} |")
print()
print("| | median | range |")
print("|---|---|---|")
print(f"| Fmax (MHz) | {statistics.median(mhz):.1f} | {min(mhz):.1f}–{max(mhz):.1f} |")
print(f"| logic cells (ICESTORM_LC) | {rows[0][2]} of {rows[0][3]} | |")
print(f"| SB_MAC16 (ICESTORM_DSP) | {rows[0][4]} of {rows[0][5]} | |")
print()
print("Per seed: " + ", ".join(f"{r[0]}: {float(r[1]):.1f}" for r in rows) + " MHz.")
print()
print("Each unit's own netlist (`specgen synth --dsp --verify --verify-exhaustive`: every (cos_g, n)")
print("through yosys's netlist under Verilator, against the golden model):")
print()
for v in verify:
    print(f"- {v}")
print()
print("SB_MAC16 without an output register (each unit's `specgen synth`):")
print()
for u in unreg:
    print(f"- {u}")
PY
bench_stamp "SEEDS=${SEEDS:-5} scripts/bench_two_units.sh" >> benchmarks/two-units.md
cat benchmarks/two-units.md
