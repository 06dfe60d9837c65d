"""A step of scripts/bench_hw.sh (its arguments as there: sys.argv[1:])."""
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
