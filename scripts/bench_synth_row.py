#!/usr/bin/env python3
"""One bench row as a JSON line: `specgen synth --json`'s figures (an empty row when it wrote
none) and the last exhaustive Verilator count of its log (`--verify`), with the KEY=VALUE
pairs given (the configuration, the toolchain, the verdict). The bench scripts' one reader.
    bench_synth_row.py SYNTH.json SYNTH.log KEY=VALUE..."""
import json, re, sys

synth, log, pairs = sys.argv[1], sys.argv[2], sys.argv[3:]
try:
    d = json.load(open(synth))
except Exception:
    d = {}
checked = re.findall(r"under Verilator: (\d+) cycles, (\d+) checked, (\d+) mismatches", open(log).read())
row = dict(p.split("=", 1) for p in pairs)
row.update(stages=d.get("stages"), lc=d.get("logic_cells"), ff=d.get("flip_flops"), dsp=d.get("dsp_blocks"), bram=d.get("block_rams"),
           seeds=d.get("fmax_seeds_capped") or d.get("fmax_seeds", []), nextpnr_seeds=d.get("fmax_seeds", []), fmax=d.get("fmax_mhz"), nextpnr=d.get("fmax_route_mhz"), limit=d.get("fmax_limited_by"),
           exhaustive=checked[-1] if checked else None)
print(json.dumps(row))
