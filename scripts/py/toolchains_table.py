"""A step of scripts/bench_toolchains.sh (its arguments as there: sys.argv[1:])."""
import json, sys, re
rows = [json.loads(l) for l in open(sys.argv[1])]
out = ["## Toolchains: every model's iCE40 operating point on yosys 0.23 and 0.70", "",
       "`scripts/bench_toolchains.sh` (SEEDS=%d): `specgen synth --dsp --verify --verify-exhaustive`, the netlist of each yosys" % max(len(r["seeds"]) for r in rows),
       "simulated with that yosys's own iCE40 cell models against the golden model on every (cos_g, n) under Verilator;",
       "Fmax from that toolchain's nextpnr-ice40, median (range) over seeds, logic cells with the serial-I/O wrapper.", "",
       "| model | stages | toolchain | netlist (exhaustive, Verilator) | logic cells | SB_MAC16 | FF | Fmax MHz |", "|---|---|---|---|---|---|---|---|"]
for r in rows:
    ex = r["exhaustive"]
    net = ("right, %s of %s cycles checked, %s mismatches" % (ex[1], ex[0], ex[2])) if ex and r["verdict"] == "right" else "**WRONG** (see the log)"
    s = r["seeds"]
    f = "%.1f (%.1f–%.1f)" % (r["fmax"], min(s), max(s)) if s else "–"
    out.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (r["model"], r["stages"], r["versions"], net, r["lc"], r["dsp"], r["ff"], f))
print("\n".join(out))
