#!/usr/bin/env bash
# Exhaustive co-simulation of the default unit against the floor it cannot beat: a bare
# Verilator loop over the same (cos_g, n) inputs on as many threads (tb/bare_loop.cpp: no
# stream, no golden model, no checks). Prints both wall-clock times and their ratio, each the
# best of RUNS (default 3), with the simulator already built for both.
#   scripts/bench_cosim_ratio.sh
source "$(dirname "$0")/bench_common.sh"
runs=${RUNS:-3}
export SPECGEN_CACHE_DIR="$work/cache"
$bin generate --out "$work/rtl" >/dev/null 2>&1
F=15; N=10; B=8; threads=$(nproc)
cp tb/bare_loop.cpp "$work/rtl/"
( cd "$work/rtl" && verilator --cc --exe --build -O3 --prefix Vdut --top-module specular_unit -Wno-fatal -Wno-lint -Wno-style \
    -Mdir obj -o ../bare -CFLAGS "-O2 -DF=$F -DN=$N -DB=$B -DTHREADS=$threads" -MAKEFLAGS OPT_FAST=-O2 \
    specular_unit.v bare_loop.cpp >/dev/null 2>&1 )
$bin cosim --rtl "$work/rtl" --vectors 10 >/dev/null
best() { sort -n | head -1; }
bare=$(for _ in $(seq "$runs"); do ( cd "$work/rtl"; s=$(date +%s.%N); ./bare >/dev/null; e=$(date +%s.%N); awk -v a="$s" -v b="$e" 'BEGIN { printf "%.3f\n", b - a }' ); done | best)
cosim=$(for _ in $(seq "$runs"); do s=$(date +%s.%N); $bin cosim --rtl "$work/rtl" --exhaustive --jobs "$threads" >/dev/null; e=$(date +%s.%N); awk -v a="$s" -v b="$e" 'BEGIN { printf "%.3f\n", b - a }'; done | best)
cosim1=$(for _ in $(seq "$runs"); do s=$(date +%s.%N); $bin cosim --rtl "$work/rtl" --exhaustive --jobs 1 >/dev/null; e=$(date +%s.%N); awk -v a="$s" -v b="$e" 'BEGIN { printf "%.3f\n", b - a }'; done | best)
ratio=$(awk -v a="$cosim" -v b="$bare" 'BEGIN { printf "%.2f", a / b }')
echo "bare Verilator loop, $threads threads: $bare s"
echo "specgen cosim --exhaustive --jobs $threads: $cosim s (--jobs 1: $cosim1 s)"
echo "ratio: $ratio"
