"""A step of scripts/bench_hw.sh (its arguments as there: sys.argv[1:])."""
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
