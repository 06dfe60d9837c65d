#!/usr/bin/env bash
# Regenerates BENCHMARKS.md: generator, golden-model and co-simulation speed on this machine.
# Usage: scripts/bench.sh   (needs verilator; builds the release binary first)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q
bin=target/release/specgen
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export SPECGEN_CACHE_DIR="$work/cache"
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }
cycles() { sed -E 's/.*: ([0-9]+) cycles.*/\1/' <<<"$1"; }

t0=$(now); $bin generate --out "$work/rtl" >/dev/null; t1=$(now); gen=$(secs "$t0" "$t1")
t0=$(now); $bin generate --out "$work/rtl_exact" --rounding exact --stages 3 >/dev/null; t1=$(now); gen_exact=$(secs "$t0" "$t1")

t0=$(now); cold=$($bin cosim --rtl "$work/rtl" --vectors 1000); t1=$(now); cold_total=$(secs "$t0" "$t1")
build=$(sed -E 's/.*build ([0-9.]+) s.*/\1/' <<<"$cold")
t0=$(now); exh=$($bin cosim --rtl "$work/rtl" --exhaustive); t1=$(now); exh_total=$(secs "$t0" "$t1")
exh_check=$(sed -E 's/.*check ([0-9.]+) s.*/\1/' <<<"$exh")
exh_rate=$(sed -E 's/.*\(([0-9.]+) M cycles\/s\).*/\1/' <<<"$exh")
$bin cosim --rtl "$work/rtl_exact" --vectors 10 >/dev/null
t0=$(now); exh2=$($bin cosim --rtl "$work/rtl_exact" --exhaustive); t1=$(now); exh2_total=$(secs "$t0" "$t1")
exh2_rate=$(sed -E 's/.*\(([0-9.]+) M cycles\/s\).*/\1/' <<<"$exh2")
t0=$(now); rnd=$($bin cosim --rtl "$work/rtl" --vectors 10000000); t1=$(now); rnd_total=$(secs "$t0" "$t1")
rnd_rate=$(sed -E 's/.*\(([0-9.]+) M cycles\/s\).*/\1/' <<<"$rnd")
$bin cosim --rtl "$work/rtl" --simulator icarus --vectors 10 >/dev/null
t0=$(now); ic=$($bin cosim --rtl "$work/rtl" --simulator icarus --vectors 100000); t1=$(now); ic_total=$(secs "$t0" "$t1")
ic_rate=$(sed -E 's/.*\(([0-9.]+) M cycles\/s\).*/\1/' <<<"$ic")

cat > BENCHMARKS.md <<MD
# Benchmarks

Hardware (area, DSPs, Fmax of lean / paper / blinn-pow): [\`BENCHMARKS-hw.md\`](BENCHMARKS-hw.md), from \`scripts/bench_hw.sh\`.

Produced by \`scripts/bench.sh\` on $(nproc) cores ($(uname -m)), $(verilator --version | head -1),
$(iverilog -V 2>/dev/null | head -1 | cut -c1-40). Wall-clock seconds of whole commands.

## Generator

| command | seconds |
|---|---|
| \`specgen generate --out DIR\` (defaults) | $gen |
| \`specgen generate --out DIR --rounding exact --stages 3\` | $gen_exact |

## Co-simulation (default configuration unless noted)

| run | cycles | end to end (s) | check (s) | M cycles/s |
|---|---|---|---|---|
| Verilator cold build (\`--vectors 1000\`) | $(cycles "$cold") | $cold_total | build $build | |
| \`--exhaustive\`, build cached | $(cycles "$exh") | $exh_total | $exh_check | $exh_rate |
| \`--exhaustive\`, \`--rounding exact --stages 3\`, cached | $(cycles "$exh2") | $exh2_total | | $exh2_rate |
| \`--vectors 10000000\` (random, corners first) | $(cycles "$rnd") | $rnd_total | | $rnd_rate |
| Icarus, \`--vectors 100000\` | $(cycles "$ic") | $ic_total | | $ic_rate |

Raw lines:

\`\`\`
$cold
$exh
$exh2
$rnd
$ic
\`\`\`
MD
echo "wrote BENCHMARKS.md"
