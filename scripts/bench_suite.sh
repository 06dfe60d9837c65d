#!/usr/bin/env bash
# The tests outside the suite's 10-minute budget (marked `#[ignore = "heavy: …"]`: deep
# pipelines co-simulated exhaustively, cocotb and FuseSoC flows, place-and-route of default-width
# units on both families, the pipelining proof), each run and timed with cargo-nextest; writes
# benchmarks/suite.md with every heavy test's verdict and time. The multi-seed Fmax claim is
# scripts/bench_hw.sh's. Usage: bash scripts/bench_suite.sh
set -euo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp); trap 'rm -f "$log"' EXIT
status=0
cargo nextest run --release --no-fail-fast --run-ignored only -E 'not test(fully_pipelined_units_reach_their_clocks_on_the_up5k_on_both_yosys)' 2>&1 | tee "$log" || status=$?
{
    echo "# The heavy tests (scripts/bench_suite.sh)"
    echo
    echo "Run at $(git rev-parse --short HEAD) on $(nproc) cores, $(date -u +%Y-%m-%d): the tests the suite leaves out of its"
    echo "10-minute budget (\`#[ignore = \"heavy: …\"]\`), each with its verdict and time (cargo-nextest)."
    echo
    echo "| test | verdict | seconds |"
    echo "|---|---|---|"
    grep -E '^ +(PASS|FAIL|SIGSEGV|SIGABRT|SIGKILL|TIMEOUT) \[' "$log" | sort -u |
        sed -E 's/^ +([A-Z]+) \[ *([0-9.]+)s\] (\([^)]*\) )?specgen::suite (.*)$/| `\4` | \1 | \2 |/'
} > benchmarks/suite.md
cat benchmarks/suite.md
exit $status
