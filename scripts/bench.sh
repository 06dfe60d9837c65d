#!/usr/bin/env bash
# Regenerates benchmarks/speed.md: generator, golden-model and co-simulation speed on this machine.
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
t0=$(now); $bin generate --out "$work/rtl_fitted" --model fitted >/dev/null; t1=$(now); gen_fitted=$(secs "$t0" "$t1")
t0=$(now); $bin generate --out "$work/rtl_blinn" --model blinn >/dev/null; t1=$(now); gen_blinn=$(secs "$t0" "$t1")
t0=$(now); $bin eval --model fitted --cos 0.5 --n 7 >/dev/null; t1=$(now); fit_only=$(secs "$t0" "$t1")

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
for m in fitted blinn; do $bin cosim --rtl "$work/rtl_$m" --vectors 10 >/dev/null; done
t0=$(now); exf=$($bin cosim --rtl "$work/rtl_fitted" --exhaustive); t1=$(now); exf_total=$(secs "$t0" "$t1")
t0=$(now); exb=$($bin cosim --rtl "$work/rtl_blinn" --exhaustive); t1=$(now); exb_total=$(secs "$t0" "$t1")
rate() { sed -E 's/.*\(([0-9.]+) M cycles\/s\).*/\1/' <<<"$1"; }
ratio=$(RUNS=5 scripts/bench_cosim_ratio.sh)

cat > benchmarks/speed.md <<MD
# Benchmarks

Hardware (area, DSPs, Fmax of every model): [\`benchmarks/hw.md\`](benchmarks/hw.md), from \`scripts/bench_hw.sh\`.

Produced by \`scripts/bench.sh\` on $(nproc) cores ($(uname -m)), $(verilator --version | head -1),
$(iverilog -V 2>/dev/null | head -1 | cut -c1-40). Wall-clock seconds of whole commands.

## Generator

| command | seconds |
|---|---|
| \`specgen generate --out DIR\` (defaults) | $gen |
| \`specgen generate --out DIR --rounding exact --stages 3\` | $gen_exact |
| \`specgen generate --out DIR --model fitted\` (the minimax fit of 1023 n, the fidelity sweep) | $gen_fitted |
| \`specgen generate --out DIR --model blinn\` (tables, the fidelity sweep) | $gen_blinn |
| \`specgen eval --model fitted ...\` (the fit alone, no sweep) | $fit_only |

Every \`generate\` measures the manifest's \`blinn_error_max\`/\`_mean\` with the golden model over
all 33.5 M (cos_g, n) of the default configuration (2^26 points at most); a row is evaluated
from its first non-zero output (the outputs are monotone in cos_g), below it every output is zero.
fitted's time is mostly its minimax fit.

## Co-simulation (default configuration unless noted)

| run | cycles | end to end (s) | check (s) | M cycles/s |
|---|---|---|---|---|
| Verilator cold build (\`--vectors 1000\`) | $(cycles "$cold") | $cold_total | build $build | |
| \`--exhaustive\`, build cached | $(cycles "$exh") | $exh_total | $exh_check | $exh_rate |
| \`--exhaustive\`, \`--rounding exact --stages 3\`, cached | $(cycles "$exh2") | $exh2_total | | $exh2_rate |
| \`--vectors 10000000\` (random, corners first) | $(cycles "$rnd") | $rnd_total | | $rnd_rate |
| Icarus, \`--vectors 100000\` | $(cycles "$ic") | $ic_total | | $ic_rate |
| \`--model fitted --exhaustive\`, cached | $(cycles "$exf") | $exf_total | | $(rate "$exf") |
| \`--model blinn --exhaustive\`, cached | $(cycles "$exb") | $exb_total | | $(rate "$exb") |

Raw lines:

\`\`\`
$cold
$exh
$exh2
$rnd
$ic
$exf
$exb
\`\`\`

## Co-simulation against the bare Verilator loop

\`scripts/bench_cosim_ratio.sh\` (best of 5 runs, $(nproc) cores): the default unit's exhaustive
sweep through \`specgen cosim --exhaustive\`, and through a bare loop over the same inputs
(\`tb/bare_loop.cpp\`: the Verilator model alone, one thread a core, no stream, no golden
model, no checks).

\`\`\`
$ratio
\`\`\`

Where the time went, and what took it away (\`perf record\` of \`--jobs 1\`): the sweep is made
inside the harness (\`SPECGEN_SWEEP\`), so no input stream crosses a pipe; a \`valid\` unit
returns one 64-bit digest a batch of 16 384 cycles instead of its records (a batch whose
digest differs is run again with records, which find and describe the first mismatch); the
golden model evaluates a batch at once, in u64 where its datapath fits; the checker keeps the
cycles due instead of making them again; a combinational unit is evaluated once a cycle, not
again at a rising edge it does not read; the simulator cache is keyed by the tool's file
rather than by running \`verilator --version\` (30 ms a call). Left: the Verilator model's own
evaluation (the floor), the harness's sweep and hashing, and the golden model's evaluation and
digest on the other core.
MD
source scripts/bench_stamp.sh
bench_stamp "scripts/bench.sh" >> benchmarks/speed.md
echo "wrote benchmarks/speed.md"
