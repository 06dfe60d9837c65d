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
    python3 - "$WORK/$family/plan/points.json" "$WORK/$family-extra/plan/points.json" > "data/explore/$family.json" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
e["points"] = [p for p in e["points"] if p["measured"]]
seen = {p["id"] for p in e["points"]}
for p in json.load(open(sys.argv[2]))["points"]:
    if p["measured"] and p["id"] not in seen:
        e["points"].append(p)
print(json.dumps(e, indent=1))
PY
done
python3 - "$WORK" ${FAMILIES:-ice40 ecp5} > benchmarks/explore.md <<'PY'
import json, os, sys, statistics
work, families = sys.argv[1], sys.argv[2:]
print("# The front of accuracy against hardware\n")
print("`specgen explore` over every model, F and FI in 8, 10, 12, 15 (the cos_g and intensity widths;")
print("N = 10, B = 8 fixed), at the depths the delay model predicts for each of the family's clocks and")
print("at the deepest. Accuracy is the golden model's over every (cos_g <= 1.0, n) (max, mean, RMS of")
print("|intensity - cos^n| at the port's codes) and the sphere of `specgen render` against float cos^n at")
print("the exact cos (PSNR; the largest step between neighbouring pixels beyond the float image's, which")
print("shows banding and counts cos_g's quantisation). Every point on or near the estimated front is")
print("measured: synthesized and placed with nextpnr seeds 1..3, one Snakemake job per seed; Fmax is the")
print("median (range) of the seeds, each capped by the limits of the blocks the unit uses; logic cells")
print("include the serial-I/O wrapper. The front at a clock: the measured points reaching it that no")
print("other beats on both max error and logic cells. `generate --max-error E --target-mhz F` chooses")
print("the cheapest measured point meeting both from these data (`data/explore/<family>.json`, which")
print("also holds the units measured beside the front: the two-unit recipe's budgets on the UP5K,")
print("lean's table as logic on the ECP5; every point of those: `explore/<family>/extra-points.csv`).\n")
for fam in families:
    e = json.load(open(os.path.join(work, fam, "plan", "points.json")))
    pts = e["points"]
    meas = [p for p in pts if p["measured"] and p["measured"]["fmax_mhz"]]
    tools = meas[0]["measured"]["tools"] if meas else {}
    print(f"## {e['part']}\n")
    print(f"{len(pts)} points, {len(meas)} measured (seeds {', '.join(map(str, e['seeds']))}); tools: " + "; ".join(f"{k} {v}" for k, v in sorted(tools.items())) + ".\n")
    print(f"![the front on the {e['part']}](explore/{fam}/front.svg)\n")
    print("Every point: [points.csv](explore/" + fam + "/points.csv); the fronts: [front.csv](explore/" + fam + "/front.csv).\n")
    for mhz in e["clocks"]:
        on = sorted([p for p in pts if mhz in p["front"]], key=lambda p: p["measured"]["logic_cells"] or 0)
        print(f"### Front at {mhz:g} MHz\n")
        print("| unit | F/FI | stages | max error | RMS error | PSNR (dB) | banding step | logic cells | DSP | BRAM | Fmax MHz, median (range) |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for p in on:
            m, a = p["measured"], p["accuracy"]
            lo, hi = min(m["fmax_seeds"]), max(m["fmax_seeds"])
            print(f"| {p['model']}{' --dsp-budget %d' % p['dsp_budget'] if p['dsp_budget'] is not None else ''}{' --rom-style ' + p['rom_style'] if p['rom_style'] != 'file' else ''} | {p['cos_frac_bits']}/{p['intensity_frac_bits']} | {p['stages']} | {a['max']:.3g} | {a['rms']:.3g} | {a['psnr_db']:.1f} | {a['max_step_excess']:.3g} | {m['logic_cells']} | {m['dsp_blocks']} | {m['block_rams']} | {m['fmax_mhz']:.1f} ({lo:.1f}-{hi:.1f}) |")
        print()
PY
bench_stamp "scripts/bench_explore.sh" >> benchmarks/explore.md
echo "wrote benchmarks/explore.md" >&2
