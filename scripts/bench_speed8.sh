#!/usr/bin/env bash
# Every model at its deepest ECP5 pipeline on the fastest part, LFE5U-25F speed grade 8
# (`synth --target ecp5 --speed 8`: nextpnr-ecp5 places for grade 8, and the blocks' limits are
# read at grade 8 — a DP16KD's clock pulse allows 271.4 MHz there). Fmax over nextpnr seeds
# 1..$SEEDS (median, range), never above a block's limit. The delay model of --target-mhz is
# calibrated on grade 6, so the depth is each model's deepest (`--stages` at its maximum).
# Rewrites the "ECP5 speed grade 8" section of benchmarks/hw.md.
#   SEEDS=5 scripts/bench_speed8.sh
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
# every model the generator has but blinn-pow (73 DSP blocks: it fits neither part)
for model in $(models); do
    [ "$model" = blinn-pow ] && continue
    dir="$work/$model"
    stages=$(max_stages --model "$model" --target ecp5)
    $bin generate --out "$dir" --model "$model" --target ecp5 --stages "$stages" >/dev/null 2>&1
    $bin synth --rtl "$dir" --target ecp5 --speed 8 --dsp --seeds "$seeds" --json "$work/$model.json" > "$work/$model.log" 2>&1 || { cat "$work/$model.log" >&2; exit 1; }
    MODEL=$model STAGES=$stages python3 scripts/py/speed8_row.py "$work/$model.json" >> "$rows"
done
python3 scripts/py/speed8_table.py "$rows" "$seeds"
