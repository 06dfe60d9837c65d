# Sourced by the bench and calibration scripts: strict mode, the repository as the working
# directory, a release build in $bin, a scratch directory $work removed on exit, and
# max_stages ARGS… (the most --stages a configuration takes, read from the generator's own
# range error, which exits 2).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cargo build --release -q
bin=target/release/specgen
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
max_stages() { { $bin generate --out "$work/probe" --stages 4294967295 "$@" 2>&1 || true; } | sed -n 's/.*allowed 0\.\.=\([0-9]*\).*/\1/p'; }
