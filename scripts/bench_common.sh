# Sourced by the bench and calibration scripts: strict mode, the repository as the working
# directory, a release build in $bin, a scratch directory $work removed on exit, and
# max_stages ARGS… (the most --stages a configuration takes, read from the generator's own
# range error, which exits 2), models (every model the generator has, from its own list of
# --model values), and the wide widths of the ECP5 target in ${wide[@]}.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cargo build --release -q
bin="${CARGO_TARGET_DIR:-target}/release/specgen"   # (a target directory of its own: CARGO_TARGET_DIR)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
# what the binary offers, from `specgen info --json` (never from an error message's words)
models() { $bin info --json | python3 -c 'import json, sys; print(" ".join(json.load(sys.stdin)["models"]))'; }
# the models a part can hold, as calibration and benches name their datapaths: lean for
# quadratic, every other but blinn-pow (73 DSP blocks: it fits neither part)
placeable() { for m in $(models); do case $m in quadratic) echo lean ;; blinn-pow) ;; *) echo "$m" ;; esac; done; }
max_stages() { $bin info --json "$@" | python3 -c 'import json, sys; print(json.load(sys.stdin)["configuration"]["deepest_stages"])'; }
# the wide configuration: F=18, N=11, B=10, FI=18, KF=20
wide=(--cos-frac-bits 18 --n-bits 11 --color-bits 10 --intensity-frac-bits 18 --k-frac-bits 20)
# the narrow configuration: F=8, N=6, B=4, FI=8 (the delay model's calibration spans it to the
# defaults: F=15, N=10, B=8, FI=15)
narrow=(--cos-frac-bits 8 --n-bits 6 --color-bits 4 --intensity-frac-bits 8)
# the generate flags of a configuration `model[:wide|:narrow]`: --model and its widths
config_args() {
    local model=${1%%:*}
    [ "$model" != lean ] && printf '%s\n' --model "$model"
    case $1 in *:wide) printf '%s\n' "${wide[@]}" ;; *:narrow) printf '%s\n' "${narrow[@]}" ;; esac
    return 0
}
# bench_stamp CMD: the provenance line that ends every benchmark file
source "$(dirname "${BASH_SOURCE[0]}")/bench_stamp.sh"
# sweep_units FAMILY SEEDS MODE DIR...: measures the generated units DIR... (each of FAMILY) as a
# sweep on Snakemake (scripts/sweep.sh: every core here, a cluster with SWEEP_ARGS="--profile
# scripts/sweep/profiles/slurm"), one job per unit and nextpnr seed 1..SEEDS, MODE dsp (the hard
# multipliers, `synth --dsp`) or nodsp (the products in the fabric), each result kept under its
# fingerprint in ${SWEEP_RESULTS:-target/bench-sweep}/FAMILY: a bench interrupted and run again
# measures only what is missing, and a unit the generator now writes otherwise is measured anew.
# Then each unit's results over its seeds are written beside it as DIR.MODE.json (what `synth
# --seeds SEEDS --json` writes) and DIR.MODE.measured.json (its point of `specgen explore
# --unit`'s points.json).
sweep_units() {
    local family=$1 seeds=$2 mode=$3; shift 3
    [ $# -gt 0 ] || return 0
    local results="${SWEEP_RESULTS:-target/bench-sweep}/$family" plan
    plan=$(mktemp -d "$work/plan-XXXXXX")
    local units=(); for d in "$@"; do units+=(--unit "$d"); done
    [ "$mode" = nodsp ] && units+=(--no-dsp)
    mkdir -p "$results"
    $bin explore --out "$plan/p" --target "$family" --seeds "$seeds" "${units[@]}" >/dev/null
    # shellcheck disable=SC2086 # SWEEP_ARGS is a list of options
    SPECGEN=$bin scripts/sweep.sh "$plan/p/jobs.json" "$results" ${SWEEP_ARGS:-} >&2
    $bin explore --out "$plan/p" --target "$family" --seeds "$seeds" "${units[@]}" --results "$results" >/dev/null
    python3 scripts/py/sweep_unit_results.py "$plan/p" "$mode" "$@"
}
# measured_text DIR [MODE]: a unit's measured Fmax (DIR.MODE.measured.json, MODE dsp by
# default) as "median (min-max)" over its seeds, each seed capped by a block's limit; where a
# limit caps one, nextpnr's own figures follow; "-" when place-and-route failed
measured_text() {
    python3 scripts/py/measured_text.py "$1.${2:-dsp}.measured.json"
}
