#!/usr/bin/env bash
# Checks the refusals of a `SAMPLE=N scripts/bench_target_mhz.sh` table (IN, default
# benchmarks/target-sample-5.md): for each configuration `generate --target-mhz` refused, its
# deepest unit (the fastest the generator writes at those widths) measured by `synth --dsp
# --seeds SEEDS` (default 3). A refusal is right where that median misses the target, and
# over-cautious where it reaches it. Writes OUT (default IN with -refused before .md).
source "$(dirname "$0")/bench_common.sh"
in=${IN:-benchmarks/target-sample-5.md}
out=${OUT:-${in%.md}-refused.md}
seeds=${SEEDS:-3}
rows="$work/rows"; : > "$rows"
right=0; wrong=0
while IFS='|' read -r _ model family widths target _; do
    model=$(echo $model); family=$(echo $family); widths=$(echo $widths); target=$(echo $target)
    IFS=/ read -r cf nb cb fi <<< "$widths"
    args=(--target "$family" --cos-frac-bits "$cf" --n-bits "$nb" --color-bits "$cb" --intensity-frac-bits "$fi")
    [ "$model" != lean ] && args+=(--model "$model")
    deep=$(max_stages "${args[@]}")
    dir="$work/u-$model-$family-$cf-$nb-$cb-$fi"
    $bin generate --out "$dir" "${args[@]}" --stages "$deep" > /dev/null
    fmax=$($bin synth --rtl "$dir" --dsp --seeds "$seeds" 2>/dev/null | sed -n 's/^  Fmax (MHz) *\([0-9.]*\) median of [0-9]* seeds (\(.*\))/\1 (\2)/p' | head -1)
    if python3 -c "import sys; sys.exit(0 if float('${fmax%% *}') >= $target else 1)"; then
        verdict="over-cautious: its deepest unit reaches F"; wrong=$((wrong + 1))
    else
        verdict="right: its deepest unit misses F"; right=$((right + 1))
    fi
    echo "| $model | $family | $widths | $target | $deep | $fmax | $verdict |" >> "$rows"
done < <(grep '| refused' "$in")
{
    echo "# The refusals of \`generate --target-mhz\` checked"
    echo
    echo "Each configuration of \`$in\` that \`generate --target-mhz\` refused, its deepest unit (the"
    echo "fastest the generator writes at those widths) measured by \`synth --dsp --seeds $seeds\` (median, min-max)."
    echo
    echo "$right refusals right (the deepest unit misses the target), $wrong over-cautious (it reaches it)."
    echo
    echo "| model | family | F/N/B/FI | target MHz | deepest stages | measured MHz | verdict |"
    echo "|---|---|---|---|---|---|---|"
    cat "$rows"
    echo
    bench_stamp "IN=$in SEEDS=$seeds scripts/bench_target_refusals.sh"
} > "$out"
echo "wrote $out" >&2
