"""A step of scripts/bench_ecp5_logic_rom.sh (its arguments as there: sys.argv[1:])."""
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
out = ["## ECP5 past the block RAM's cap: every model with its tables in LUTs", "",
       "`scripts/bench_ecp5_logic_rom.sh` (SEEDS=%d): every model with tables at its deepest on the LFE5U-25F grade 6," % max(len(r["seeds"]) for r in rows),
       "its tables in LUTs (`--rom-style logic`: each table's parts, each a function of at most 5 address bits (the lean",
       "cut-off table's of 6), then 4:1 picks by the address's top bits, a step each; a fabric flip-flop between each",
       "MULT18X18D and the carry chains around it), constrained to %s MHz (`--clock-mhz`); the lean unit also with its" % rows[0].get("clock", "250"),
       "cut-off table in a DP16KD (`--rom-style file`, the default). `specgen synth --dsp --verify --verify-exhaustive`",
       "with each yosys (its netlist against the golden model on every (cos_g, n) under Verilator), YoWASP's nextpnr-ecp5;",
       "Fmax the median (range) over seeds, never above a block's own limit (DP16KD 211.9 MHz, MULT18X18D 258.7 MHz at grade 6).", "",
       "| model | --rom-style | stages | yosys | netlist (exhaustive, Verilator) | logic cells | FF | MULT18X18D | DP16KD | Fmax MHz |",
       "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    ex = r["exhaustive"]
    net = ("right, %s of %s cycles checked, %s mismatches" % (ex[1], ex[0], ex[2])) if ex and r["verdict"] == "right" else "**WRONG** (see the log)"
    s = r["seeds"]
    f = "%.1f" % r["fmax"] if r["fmax"] else "–"
    if s:
        f += " (%.1f–%.1f; set by %s; nextpnr %.1f, %.1f–%.1f)" % (min(s), max(s), (r["limit"] or "routing").split(":")[0], r["nextpnr"] or 0, min(r["nextpnr_seeds"] or s), max(r["nextpnr_seeds"] or s))
    out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (r.get("model", "quadratic"), r["style"], r["stages"], r["versions"], net, r["lc"], r["ff"], r["dsp"], r["bram"], f))
out += ["", sys.argv[2].strip()]
print("\n".join(out))
