"""A step of scripts/bench_gowin.sh (its arguments as there: sys.argv[1:])."""
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
out = ["## Every model on the GW1NR-9", "",
       "`scripts/bench_gowin.sh` (SEEDS=%d): every model at its deepest for the Tang Nano 9K's GW1NR-LV9QN88PC6/I5" % max(len(r["seeds"]) for r in rows),
       "(`--target gowin`: every product on a MULT18X18 with its input and output registers, every table read in a pROMX9",
       "with its address and output registers), in the serial-I/O wrapper, constrained to 100 MHz. `specgen synth --dsp",
       "--verify --verify-exhaustive` with each yosys (its netlist, with specgen's MULT18X18 and pROMX9 models, against",
       "the golden model on every (cos_g, n) under Verilator), YoWASP's nextpnr-himbaechel-gowin; Fmax the median (range)",
       "over seeds. nextpnr-himbaechel times the fabric but neither block: not the MULT18X18's multiply between its own",
       "registers (no DSP timing for the GW1N), nor a pROMX9's ports (packed as a ROM cell, which its BSRAM timing lacks); no",
       "datasheet figure is built in for either: the figures leave those paths out.",
       "Logic cells: LUT4s and ALUs, or flip-flops where more (of 8 640).", "",
       "| model | stages | yosys | netlist (exhaustive, Verilator) | logic cells | FF | MULT18X18 | BSRAM | Fmax MHz | bitstream |",
       "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    ex = r["exhaustive"]
    net = ("right, %s of %s cycles checked, %s mismatches" % (ex[1], ex[0], ex[2])) if ex and r["verdict"] == "right" else "**WRONG** (see the log)"
    s = r["seeds"]
    f = "%.1f" % r["fmax"] if r["fmax"] else "–"
    if s:
        f += " (%.1f–%.1f)" % (min(s), max(s))
    packed = ("%s bytes" % r["packed"]) if r.get("packed") else ""
    lc = r["lc"] if r["lc"] is not None else "– (does not fit)"
    out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (r["model"], r["stages"], r["versions"], net, lc, r["ff"], r["dsp"], r["bram"], f, packed))
if any(r["model"] == "blinn-pow" for r in rows):
    out += ["", "blinn-pow does not fit the part (its unit at default widths wants some 73 18×18 multipliers of the GW1NR-9's 20:",
            "yosys 0.70 maps the products no cut surrounds to MULT36X36 and MULT9X9 without registers, which `synth` lists",
            "as unregistered), so it has no Fmax; its netlist is checked with specgen's models of those two, on yosys 0.70",
            "alone (0.23 infers no multiplier and puts its products in tens of thousands of LUTs)."]
out += ["", sys.argv[2].strip()]
print("\n".join(out))
