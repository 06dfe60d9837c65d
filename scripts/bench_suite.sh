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
# the ignored tests marked heavy, not the multi-seed ones (`#[ignore = "multi-seed …"]`: each
# bench script of its own runs them)
multi=$(grep -h -A1 '^#\[ignore = "multi-seed' tests/suite/*.rs | sed -n 's/^fn \([a-z0-9_]*\)(.*/test(~\1)/p' | paste -sd'|' | sed 's/|/ | /g')
filter=${multi:+"not ($multi)"}
cargo nextest run --release --no-fail-fast --run-ignored only ${filter:+-E "$filter"} 2>&1 | tee "$log" || status=$?
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
