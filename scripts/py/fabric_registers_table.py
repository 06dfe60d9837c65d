"""benchmarks/fabric-registers.md from `specgen synth --json` results: argv[1] the provenance
line, argv[2:] the results, each `YOSYS VERSION|FILE` (one a unit and yosys)."""
import json
import sys


def main(stamp, files):
    print("# `--fabric-registers` on the iCE40 UP5K\n")
    print("Each model at its deepest with `--fabric-registers`, constrained to 125 MHz, `specgen synth --dsp`")
    print("with each yosys and nextpnr-ice40: Fmax the median (range) over the seeds, logic cells")
    print("(ICESTORM_LC). nextpnr does not time the multiply inside an SB_MAC16 (153.7 MHz by IceStorm's")
    print("data); `synth` checks every block's register on the netlist.\n")
    print("| model | stages | yosys | Fmax MHz | per seed | logic cells | SB_MAC16 |")
    print("|---|---|---|---|---|---|---|")
    for entry in files:
        yosys, f = entry.split("|", 1)
        r = json.load(open(f))
        seeds = r["fmax_seeds"]
        lo, hi = min(seeds), max(seeds)
        per = ", ".join(f"{s}: {v:.1f}" for s, v in zip(r["seeds"], seeds))
        print(f"| {r['model']} | {r['stages']} | {yosys} | {r['fmax_mhz']:.1f} ({lo:.1f}–{hi:.1f}) "
              f"| {per} | {r['logic_cells']} | {r['dsp_blocks']} |")
    print(stamp)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
