#!/usr/bin/env python3
"""Fits the delay model of `generate --target-mhz` (src/timing.rs) to place-and-route data.

    scripts/fit_delay_model.py [data/delay_calibration.csv] [data/delay_model.json]

Per family, the clock period of a unit is modelled as a straight line in the plan's stage delay
estimate e (the slowest stretch of logic between two registers, summed from the datapath's
per-step estimates):

    period_ns = offset_ns + ns_per_unit * e,    Fmax = min(cap_mhz, 1000 / period_ns)

`cap_mhz` is the highest median Fmax measured on the family (the hard blocks' limit: SB_MAC16
and SB_RAM40_4K on the UP5K); the line is fitted by least squares on the units below 97 % of
it. `margin` is the largest ratio measured/predicted below 1 over the data, so that
`--target-mhz F` asks the model for F / margin: the chosen depth reached F on every
calibration point. The JSON also keeps the fit's residuals for the record.
"""
import csv
import json
import sys


def fit(rows):
    cap = max(r["fmax"] for r in rows)
    free = [r for r in rows if r["fmax"] < 0.97 * cap]
    if len(free) < 2:
        free = rows
    xs = [r["est"] for r in free]
    ys = [1000.0 / r["fmax"] for r in free]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    offset = my - slope * mx
    predict = lambda e: min(cap, 1000.0 / max(offset + slope * e, 1e-6))
    ratios = [r["fmax"] / predict(r["est"]) for r in rows]
    margin = min(1.0, min(ratios))
    return {
        "offset_ns": round(offset, 4),
        "ns_per_unit": round(slope, 4),
        "cap_mhz": round(cap, 2),
        "margin": round(margin, 4),
        "points": len(rows),
        "worst_under": round(min(ratios), 4),
        "worst_over": round(max(ratios), 4),
    }


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "data/delay_calibration.csv"
    dst = sys.argv[2] if len(sys.argv) > 2 else "data/delay_model.json"
    by_family = {}
    with open(src) as f:
        for row in csv.DictReader(f):
            if not row["fmax_mhz"]:
                continue
            by_family.setdefault(row["family"], []).append(
                {"model": row["model"], "stages": int(row["stages"]), "est": float(row["stage_delay_estimate"]), "fmax": float(row["fmax_mhz"])}
            )
    model = {family: fit(rows) for family, rows in sorted(by_family.items())}
    model["source"] = src
    with open(dst, "w") as f:
        json.dump(model, f, indent=2)
        f.write("\n")
    for family, m in model.items():
        if family != "source":
            print(f"{family}: period = {m['offset_ns']} ns + {m['ns_per_unit']} ns/unit * e, cap {m['cap_mhz']} MHz, margin {m['margin']} over {m['points']} units", file=sys.stderr)


if __name__ == "__main__":
    main()
