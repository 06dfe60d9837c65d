#!/usr/bin/env python3
"""Fits the delay model of `generate --target-mhz` (src/timing/mod.rs) to place-and-route data.

    scripts/fit_delay_model.py [data/delay_calibration.csv] [data/delay_model.json]

Per family, the clock period of a unit is modelled from the plan's slowest stretch of logic
between two registers e (`stage_delay_estimate`) and the mean stretch m (the whole datapath's
estimate over stages + 1, `stage_delay_mean`):

    period_ns = offset_ns + ns_per_unit * e + ns_per_mean_unit * m,
    Fmax = min(cap_mhz, 1000 / period_ns)

`cap_mhz` is the highest median Fmax measured on the family (the hard blocks' limit: SB_MAC16
and SB_RAM40_4K on the UP5K); `cap_up_to` is the largest e among the units that reached it (a
unit whose slowest stretch is no longer is predicted at the cap; -1: none did). The plane is fitted by least squares on every unit (those at the
cap too: a deep unit's jump to it, when the DSPs' own registers take the last cuts, is data),
with non-negative slopes (else the line in one of e, m, or a constant), once per family
("all") and once per model with three units or more (the generator uses its model's). `margin` is the worst ratio measured/predicted over the data (at most 1): `--target-mhz F`
asks the model for F / margin, so the chosen depth reached F on every calibration point. The
JSON also keeps the fit's extremes for the record. The estimates e and m of each unit are asked
of the generator as it is now ($SPECGEN, default target/release/specgen), so a change to them
needs a refit, not a new place-and-route (the CSV's two estimate columns are the generator's
at the last refit, for the reader).
"""
import csv
import json
import os
import subprocess
import sys
import tempfile


def features(family, model, stages, extra):
    """The unit's slowest and mean stretch estimates, asked of the generator as it is now (so a
    change to the estimates needs a refit, not a new place-and-route); `extra`: the generate
    flags beyond the model (the CSV's `args`, the widths)."""
    binary = os.environ.get("SPECGEN", "target/release/specgen")
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "u")
        args = [binary, "generate", "--out", out, "--target", family, "--stages", str(stages)]
        if model != "lean":
            args += ["--model", model]
        args += extra
        subprocess.run(args, check=True, capture_output=True)
        with open(os.path.join(out, "specular_unit.json")) as f:
            m = json.load(f)
    return m["stage_delay_estimate"], m["stage_delay_mean"]


def solve(a, b):
    """Solves the square system a x = b (Gaussian elimination with pivoting)."""
    n = len(b)
    m = [row[:] + [v] for row, v in zip(a, b)]
    for i in range(n):
        p = max(range(i, n), key=lambda r: abs(m[r][i]))
        m[i], m[p] = m[p], m[i]
        if abs(m[i][i]) < 1e-12:
            raise ValueError("singular")
        for r in range(n):
            if r != i:
                k = m[r][i] / m[i][i]
                m[r] = [x - k * y for x, y in zip(m[r], m[i])]
    return [m[i][n] / m[i][i] for i in range(n)]


def least_squares(rows, features):
    """period = c0 + sum(c_k * feature_k): the coefficients and the squared error."""
    xs = [[1.0] + [r[f] for f in features] for r in rows]
    ys = [1000.0 / r["fmax"] for r in rows]
    k = len(features) + 1
    ata = [[sum(x[i] * x[j] for x in xs) for j in range(k)] for i in range(k)]
    aty = [sum(x[i] * y for x, y in zip(xs, ys)) for i in range(k)]
    c = solve(ata, aty)
    err = sum((y - sum(ci * xi for ci, xi in zip(c, x))) ** 2 for x, y in zip(xs, ys))
    return c, err


def fit(rows, cap):
    """The plane (or the line, or the constant) with non-negative slopes that fits best."""
    free = rows
    best = None
    for features in (["est", "mean"], ["mean"], ["est"], []):
        if len(free) < len(features) + 1:
            continue
        try:
            c, err = least_squares(free, features)
        except ValueError:
            continue
        if any(ci < 0 for ci in c[1:]):
            continue
        if best is None or err < best[2] - 1e-9:
            best = (features, c, err)
    features, c, _ = best
    coef = dict(zip(features, c[1:]))
    # units whose slowest stretch is no longer than one that reached the cap reach it too, as
    # long as no unit that did not reach it is as short
    below = [r["est"] for r in rows if r["fmax"] < 0.99 * cap]
    at_cap = [r["est"] for r in rows if r["fmax"] >= 0.99 * cap and r["est"] < min(below, default=float("inf"))]
    line = {
        "offset_ns": round(c[0], 4),
        "ns_per_unit": round(coef.get("est", 0.0), 4),
        "ns_per_mean_unit": round(coef.get("mean", 0.0), 4),
        "cap_mhz": round(cap, 2),
        "cap_up_to": round(max(at_cap), 4) if at_cap else -1.0,
    }

    def predict(r):
        if r["est"] <= line["cap_up_to"]:
            return cap
        return min(cap, 1000.0 / max(line["offset_ns"] + line["ns_per_unit"] * r["est"] + line["ns_per_mean_unit"] * r["mean"], 1e-6))

    # the margin is the line's: a unit predicted at the cap by `cap_up_to` was measured there
    ratios = [r["fmax"] / predict(r) for r in rows if r["est"] > line["cap_up_to"]] or [1.0]
    line.update(margin=round(min(1.0, min(ratios)), 4), points=len(rows), worst_under=round(min(ratios), 4), worst_over=round(max(ratios), 4))
    return line


# datapaths that take the family's line though never measured on their own
FAMILY_LINE = ["paper", "blinn-pow"]


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "data/delay_calibration.csv"
    dst = sys.argv[2] if len(sys.argv) > 2 else "data/delay_model.json"
    by_family = {}
    with open(src) as f:
        for row in csv.DictReader(f):
            if not row["fmax_mhz"]:
                continue
            fam, model, stages = row["family"], row["model"], int(row["stages"])
            est, mean = features(fam, model, stages, (row.get("args") or "").split())
            args = " ".join((row.get("args") or "").split())
            by_family.setdefault(fam, []).append({"model": model, "stages": stages, "est": est, "mean": mean, "fmax": float(row["fmax_mhz"]), "args": args, "digest": (row.get("rtl_sha256") or "").strip()})
    # a line per family ("all") and per model of it (three units or more): the generator uses
    # its model's line, else the family's
    model = {}
    for family, rows in sorted(by_family.items()):
        cap = max(r["fmax"] for r in rows)
        lines = {"all": fit(rows, cap)}
        for name in sorted({r["model"] for r in rows}):
            mine = [r for r in rows if r["model"] == name]
            if len(mine) >= 3:
                lines[name] = fit(mine, cap)
                # its units as measured, each with the widths it was generated at (`args`): a
                # floor for units of the same widths with stretches no longer (src/timing/mod.rs);
                # the line and its margin are fitted over every width of the grid
                ordered = sorted(mine, key=lambda r: (r["args"], r["stages"]))
                lines[name]["measured"] = [[r["est"], r["mean"], round(r["fmax"], 2)] for r in ordered]
                lines[name]["measured_args"] = [r["args"] for r in ordered]
                lines[name]["measured_stages"] = [r["stages"] for r in ordered]
                # the RTL each was measured on (empty: the row names none): a floor only where
                # it is the RTL specgen writes today
                lines[name]["measured_digest"] = [r["digest"] for r in ordered]
        # datapaths with fewer measured units than a line needs (blinn-pow does not fit the
        # parts), and the paper's (the lean datapath's operations uncut, never calibrated on its
        # own), take the family's line by name: the generator refuses a datapath this file
        # does not name ("run scripts/calibrate_delay.sh"), never falls back silently
        for name in sorted({r["model"] for r in rows} | set(FAMILY_LINE)):
            lines.setdefault(name, "all")
        model[family] = lines
    model["source"] = src
    with open(dst, "w") as f:
        json.dump(model, f, indent=2)
        f.write("\n")
    for family, lines in model.items():
        if family == "source":
            continue
        for name, m in lines.items():
            if m == "all":
                print(f"{family} {name}: the family's line", file=sys.stderr)
                continue
            print(
                f"{family} {name}: period = {m['offset_ns']} + {m['ns_per_unit']}*e + {m['ns_per_mean_unit']}*m ns, cap {m['cap_mhz']} MHz, "
                f"margin {m['margin']} (measured/predicted {m['worst_under']}..{m['worst_over']}) over {m['points']} units",
                file=sys.stderr,
            )


if __name__ == "__main__":
    main()
