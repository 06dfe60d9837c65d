#!/usr/bin/env bash
# A sweep that is interrupted and resumed never loses a job and never runs one twice:
# `specgen explore --run` over a narrow space of about 20 jobs (quadratic, F = FI = 8, N = B = 4,
# seeds 1..2, every point measured), twice:
#   1. on specgen's own slots, one nextpnr killed by SIGKILL midway, then the command run again;
#   2. on Snakemake (--engine snakemake), the sweep's snakemake killed by SIGKILL midway (its jobs
#      run on as orphans), then the command run again.
# nextpnr is run through a wrapper that logs every placement: each case must end with 20 results
# for every job and exactly one placement per job, plus one per placement killed. Writes
# benchmarks/sweep-kill.md.
source "$(dirname "$0")/bench_common.sh"
real=$(command -v nextpnr-ice40)
cat > "$work/nextpnr-ice40" <<EOF
#!/usr/bin/env bash
# logs each placement (not the version query), then runs the real nextpnr in its place
case " \$* " in *" --version "*) ;; *) echo "\$\$ \$*" >> "$work/placements.log" ;; esac
exec "$real" "\$@"
EOF
chmod +x "$work/nextpnr-ice40"
space=(--models quadratic --cos-frac-bits 8 --intensity-frac-bits 8 --n-bits 4 --color-bits 4 --measure-all --seeds 2 --clocks 50,75 --depths 12)
placements() { [ -f "$work/placements.log" ] && wc -l < "$work/placements.log" || echo 0; }
results() { find "$1" -maxdepth 1 -name '*.json' | wc -l; }
rows=()
for case in specgen snakemake; do
    rm -f "$work/placements.log"
    store=$work/$case-results
    run() { "$bin" explore --out "$work/$case-plan" --results "$store" "${space[@]}" --run --run-jobs 2 --engine "$case" --nextpnr "$work/nextpnr-ice40" "$@"; }
    run > "$work/$case-1.log" 2>&1 &
    pid=$!
    # midway: six placements started
    for _ in $(seq 600); do [ "$(placements)" -ge 6 ] && break; sleep 0.5; done
    if [ "$case" = specgen ]; then
        # one nextpnr killed by a signal (the newest), as an OOM killer or a preemption would
        pkill -KILL -n -f "$real" || true
        wait "$pid" || true
        killed=1
    else
        # the sweep's snakemake killed by SIGKILL, and the command that started it
        pkill -KILL -f "snakemake -s $store/.specgen/Snakefile" || true
        kill -KILL "$pid" 2>/dev/null || true
        wait "$pid" 2>/dev/null || true
        killed=0
    fi
    before=$(results "$store")
    run > "$work/$case-2.log" 2>&1 || tail -20 "$work/$case-2.log" >&2
    jobs=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))))' "$work/$case-plan/jobs.json")
    after=$(results "$store")
    placed=$(placements)
    # every placement that ran to its end made one result: none ran twice
    verdict=ok
    [ "$after" -eq "$jobs" ] && [ "$placed" -eq $((jobs + killed)) ] || verdict=FAILED
    rows+=("| $case | $jobs | $before | $after | $placed | $killed | $verdict |")
    echo "$case: $jobs jobs, $before results when killed, $after after the resumed run, $placed placements ($killed killed): $verdict" >&2
done
{
    echo "# A sweep killed midway and resumed"
    echo
    echo "\`specgen explore --run\` over the jobs below (quadratic, F = FI = 8, N = B = 4, nextpnr seeds 1..2,"
    echo "every point measured), two at a time; nextpnr through a wrapper that logs each placement."
    echo "*specgen*: its own slots, one nextpnr killed by SIGKILL midway, then the same command again."
    echo "*snakemake*: \`--engine snakemake\`, the sweep's snakemake killed by SIGKILL midway (its jobs run"
    echo "on as orphans, each holding its job's lock), then the same command again. A job's result is"
    echo "written whole or not at all; the resumed run runs only what has no result, and waits for a"
    echo "job still running rather than starting it beside itself."
    echo
    echo "| engine | jobs | results when killed | results after resuming | placements | killed | verdict |"
    echo "|---|---|---|---|---|---|---|"
    printf '%s\n' "${rows[@]}"
    echo
    echo "Placements = jobs + killed: every job placed once, the killed one once more, none twice."
    bench_stamp "scripts/bench_sweep_kill.sh"
} > benchmarks/sweep-kill.md
cat benchmarks/sweep-kill.md
