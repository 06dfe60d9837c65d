#!/usr/bin/env bash
# Measures what the delay model of `generate --target-mhz` (src/timing/mod.rs) is fitted to, as a
# Snakemake sweep (scripts/explore.sh: every core here, or a cluster with SWEEP_ARGS="--profile
# scripts/sweep/profiles/slurm"): for each family (iCE40 UP5K with DSPs, ECP5-25 grade 6) and
# width (the defaults F/N/B/FI 15/10/8/15, and narrow 8/6/4/8), every model a part holds at
# DEPTHS (default 10) depths spread up to its deepest (and the depths its clocks pick),
# place-and-routed with nextpnr seeds 1..SEEDS (default 2), one job per unit and seed, each
# result under its fingerprint (an interrupted calibration resumes; WORK, default
# target/calibrate, keeps them). The explorations' calibration rows (family, datapath, stages,
# the plan's slowest and mean stretch, nextpnr's median, its seeds, the generate flags beyond the
# defaults) replace the rows of the same unit in data/delay_calibration.csv; the rest stay (the
# wide lean on the ECP5). `specgen calibrate --merge` merges them and fits data/delay_model.json to the result.
# FAMILIES (default "ice40 ecp5") and MODELS (default every model but blinn-pow, which fits
# neither part) narrow it.
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-2}
out=${OUT:-data/delay_calibration.csv}
WORK=${WORK:-target/calibrate}
# (an `if`, not `[ … ] && echo`: a last model that is skipped would end the loop with status 1,
# which `set -e` takes for the assignment's failure)
models=${MODELS:-$(for m in $(models); do if [ "$m" != blinn-pow ]; then echo -n "$m,"; fi; done)}
models=${models%,}
for family in ${FAMILIES:-ice40 ecp5}; do
    for widths in default narrow; do
        case $widths in
            default) w=(--cos-frac-bits 15 --intensity-frac-bits 15 --n-bits 10 --color-bits 8) ;;
            narrow) w=(--cos-frac-bits 8 --intensity-frac-bits 8 --n-bits 6 --color-bits 4) ;;
        esac
        SPECGEN=$bin SWEEP_ARGS=${SWEEP_ARGS:-} scripts/explore.sh "$WORK/$family-$widths" --target "$family" --models "$models" \
            "${w[@]}" --depths "${DEPTHS:-10}" --measure-all --seeds "$seeds"
    done
done
[ -s "$out" ] || echo "family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args,rtl_sha256" > "$out"
merges=(); for f in "$WORK"/*/plan/calibration.csv; do merges+=(--merge "$f"); done
$bin calibrate --calibration "$out" "${merges[@]}" --rows-out "$work/merged.csv" --out "$work/model.json"
mv "$work/merged.csv" "$out"
[ "$out" = data/delay_calibration.csv ] && mv "$work/model.json" data/delay_model.json
echo "wrote $out (and, where it is the shipped one, data/delay_model.json: its fit)" >&2
