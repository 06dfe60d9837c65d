"""A step of scripts/bench_explore.sh (its arguments as there: sys.argv[1:])."""
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
