#!/usr/bin/env bash
# Regenerates benchmarks/explore.md, its figures and tables (benchmarks/explore/<family>/), and
# the explorations built into `generate --max-error` (data/explore/<family>.json: the measured
# points): `specgen explore` over every model from narrow to default widths (F, FI in
# 8,10,12,15; N = 10, B = 8) on each family, the points on or near the estimated front measured
# by a Snakemake sweep (scripts/explore.sh) over nextpnr seeds 1..3.
# FAMILIES (default "ice40 ecp5") narrows it; WORK (default target/explore) keeps the sweeps'
# results, so a run stopped midway resumes where it stopped; SWEEP_ARGS goes to Snakemake
# (e.g. "--profile scripts/sweep/profiles/slurm" for a cluster).
source "$(dirname "$0")/bench_common.sh"
WORK=${WORK:-target/explore}
for family in ${FAMILIES:-ice40 ecp5}; do
    args=(--target "$family")
    # the ECP5 writes lean's table as logic too; its space is larger, so only what stands
    # within 10% of the estimated front is measured
    [ "$family" = ecp5 ] && args+=(--rom-style file,logic --near 0.1)
    SPECGEN=$bin SWEEP_ARGS=${SWEEP_ARGS:-} scripts/explore.sh "$WORK/$family" "${args[@]}"
    # beside the front, every point of the units users build to share a device or pass a block
    # RAM's limit, measured at default widths: the budgets of the two-unit recipe on the UP5K,
    # lean's table as logic on the ECP5
    case $family in
        ice40) extra=(--models quadratic,blinn --cos-frac-bits 15 --intensity-frac-bits 15 --dsp-budget 3,5 --measure-all) ;;
        ecp5) extra=(--models quadratic --cos-frac-bits 15 --intensity-frac-bits 15 --rom-style logic --measure-all) ;;
    esac
    SPECGEN=$bin SWEEP_ARGS=${SWEEP_ARGS:-} scripts/explore.sh "$WORK/$family-extra" --target "$family" "${extra[@]}"
    mkdir -p "benchmarks/explore/$family" data/explore
    cp "$WORK/$family/plan/"{front.svg,front.csv,points.csv,calibration.csv} "benchmarks/explore/$family/"
    cp "$WORK/$family-extra/plan/points.csv" "benchmarks/explore/$family/extra-points.csv"
    # the built-in exploration: the measured points of both
    python3 scripts/py/explore_merge_points.py "$WORK/$family/plan/points.json" "$WORK/$family-extra/plan/points.json" > "data/explore/$family.json"
done
python3 scripts/py/explore_table.py "$WORK" ${FAMILIES:-ice40 ecp5} > benchmarks/explore.md
bench_stamp "scripts/bench_explore.sh" >> benchmarks/explore.md
echo "wrote benchmarks/explore.md" >&2
