# Sourced by the bench and calibration scripts: strict mode, the repository as the working
# directory, a release build in $bin, a scratch directory $work removed on exit, and
# max_stages ARGS… (the most --stages a configuration takes, read from the generator's own
# range error, which exits 2), models (every model the generator has, from its own list of
# --model values), and the wide widths of the issue's ECP5 target in ${wide[@]}.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cargo build --release -q
bin="${CARGO_TARGET_DIR:-target}/release/specgen"   # (a target directory of its own: CARGO_TARGET_DIR)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
models() { { $bin generate --model '?' 2>&1 || true; } | sed -n 's/.*possible values: \(.*\)\]/\1/p' | tr -d ','; }
# the models a part can hold, as calibration and benches name their datapaths: lean for
# quadratic, every other but blinn-pow (73 DSP blocks: it fits neither part)
placeable() { for m in $(models); do case $m in quadratic) echo lean ;; blinn-pow) ;; *) echo "$m" ;; esac; done; }
max_stages() { { $bin generate --out "$work/probe" --stages 4294967295 "$@" 2>&1 || true; } | sed -n 's/.*allowed 0\.\.=\([0-9]*\).*/\1/p'; }
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
