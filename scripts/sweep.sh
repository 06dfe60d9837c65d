#!/usr/bin/env bash
# Runs a sweep (`specgen explore`'s jobs.json) on Snakemake: on this machine on every core by
# default, on a cluster with a profile (scripts/sweep/profiles/slurm). Each job's result is
# RESULTS/<fingerprint>.json; run again after an interruption and only what is missing runs
# (a result is never run again because the Snakefile changed: its fingerprint says what it is).
#   scripts/sweep.sh JOBS.json RESULTS_DIR [snakemake options, e.g. --cores 1 or --profile P]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 JOBS.json RESULTS_DIR [snakemake options]" >&2; exit 2; }
jobs=$(realpath "$1"); results=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
command -v snakemake >/dev/null 2>&1 || python3 -m pip install -q "snakemake==9.27.1"
specgen=${SPECGEN:-$(command -v specgen || echo "$here/../target/release/specgen")}
[ -x "$specgen" ] || { echo "$0: specgen not found: cargo install --path . (or SPECGEN=path)" >&2; exit 1; }
# the jobs run in RESULTS_DIR: a program named by a relative path is named absolutely
specgen=$(realpath "$specgen")
case ${YOSYS:-} in */*) YOSYS=$(realpath "$YOSYS") ;; esac
case ${NEXTPNR:-} in */*) NEXTPNR=$(realpath "$NEXTPNR") ;; esac
mkdir -p "$results"
results=$(realpath "$results")
cores=(--cores all)
for a in "$@"; do case $a in --cores|--cores=*|-c*|--jobs|--jobs=*|-j*|--profile|--profile=*) cores=();; esac; done
# a lock left by a sweep that was killed is stale unless a snakemake on this directory runs
if [ -d "$results/.snakemake/locks" ] && ! pgrep -f -- "--directory $results( |$)" >/dev/null; then
    snakemake -s "$here/sweep/Snakefile" --directory "$results" --config jobs="$jobs" specgen="$specgen" --unlock >/dev/null 2>&1 || true
fi
# each job writes its result whole or not at all (specgen measure writes atomically), so a result
# there is complete even when Snakemake was killed before it recorded so: --ignore-incomplete
# keeps it (--rerun-incomplete would run a finished job again)
exec snakemake -s "$here/sweep/Snakefile" --directory "$results" --config jobs="$jobs" specgen="$specgen" \
    ${YOSYS:+yosys="$YOSYS"} ${NEXTPNR:+nextpnr="$NEXTPNR"} \
    --ignore-incomplete --rerun-triggers mtime --keep-going --printshellcmds "${cores[@]}" "$@"
