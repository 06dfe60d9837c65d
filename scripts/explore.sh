#!/usr/bin/env bash
# One command for an exploration: plan it (`specgen explore`), measure the points on or near
# the estimated front on Snakemake (scripts/sweep.sh: every core here, or a cluster with
# `--profile scripts/sweep/profiles/slurm` in SWEEP_ARGS), then merge the results into the
# measured front. Run it again after an interruption: only the missing jobs run.
#   scripts/explore.sh OUT [specgen explore options, e.g. --target ecp5 --rom-style file,logic]
# OUT/plan holds the exploration (points.json/.csv, front.csv/.svg, calibration.csv),
# OUT/results every job's result under its fingerprint.
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 OUT [specgen explore options]" >&2; exit 2; }
out=$1; shift
here=$(cd "$(dirname "$0")" && pwd)
specgen=${SPECGEN:-$(command -v specgen || echo "$here/../target/release/specgen")}
mkdir -p "$out/results"
"$specgen" explore --out "$out/plan" --results "$out/results" "$@"
SPECGEN=$specgen "$here/sweep.sh" "$out/plan/jobs.json" "$out/results" ${SWEEP_ARGS:-}
"$specgen" explore --out "$out/plan" --results "$out/results" "$@"
