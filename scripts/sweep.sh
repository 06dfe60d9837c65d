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
# one sweep at a time on a results directory: this one holds the lock below for its life (its
# snakemake inherits it; the jobs Snakemake starts do not). Held by another: refused. Taken:
# any Snakemake lock there is a killed sweep's, and is lifted (no process list is searched:
# a directory's name is data, never a pattern). A job still running from a killed sweep holds
# its own lock (`specgen measure`), so none starts beside itself.
exec 9>>"$results/.specgen-sweep.lock"
if ! flock -n 9; then
    echo "$0: a sweep is running on $results (it holds $results/.specgen-sweep.lock); wait for it or stop it" >&2
    exit 1
fi
export SPECGEN_SWEEP_JOBS=$jobs SPECGEN_SWEEP_SPECGEN=$specgen SPECGEN_SWEEP_YOSYS=${YOSYS:-} SPECGEN_SWEEP_NEXTPNR=${NEXTPNR:-}
cores=(--cores all)
for a in "$@"; do case $a in --cores|--cores=*|-c*|--jobs|--jobs=*|-j*|--profile|--profile=*) cores=();; esac; done
if [ -d "$results/.snakemake/locks" ]; then
    snakemake -s "$here/sweep/Snakefile" --directory "$results" --unlock >/dev/null 2>&1 || true
fi
# each job writes its result whole or not at all (specgen measure writes atomically), so a result
# there is complete even when Snakemake was killed before it recorded so: --ignore-incomplete
# keeps it (--rerun-incomplete would run a finished job again)
exec snakemake -s "$here/sweep/Snakefile" --directory "$results" \
    --ignore-incomplete --rerun-triggers mtime --keep-going --printshellcmds "${cores[@]}" "$@"
