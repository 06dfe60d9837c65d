#!/usr/bin/env bash
# What `specgen prove` proves and refutes, and how long each takes (Debian's yosys and
# yosys-abc): the valid edge at three depths; the delivered values against the valid twin
# (--datapath, narrow); pipelining against the depth-0 twin (lean and
# fitted at reduced widths, and at default widths with their delay lines in RAM); the ready and axis edges at three
# depths at default widths (k-induction over the port checker's properties, the unit's own
# assertions its lemmas); and each of the seven
# handshake faults the simulation suite injects (tests/suite/interfaces.rs), refuted with a
# counterexample. Writes benchmarks/prove.md.
# Each fault is refuted as the suite refutes it: a bounded search of 24 edges (--depth 24), which
# the port checker joins. LIMIT is each engine's guard (out of time: not a verdict).
#   LIMIT=1200 scripts/bench_prove.sh
source "$(dirname "$0")/bench_common.sh"
limit=${LIMIT:-1200}
rows="$work/rows.md"; : > "$rows"
row() { # what, command...
    local what=$1; shift
    local s e out verdict
    s=$(date +%s.%N)
    out=$("$@" 2>&1) && verdict="proved$(sed -n 's/.*\(k = [0-9]*\).*/, \1/p' <<< "$out" | head -1)" || verdict=$(sed -n 's/.*: \(a property fails [0-9]* clock edges\{0,1\}[^;]*\).*/refuted: \1/p; s/.*: \(undecided\): .*\(ran out of time\).*/\1, \2/p; s/.*: \(undecided\): .*/\1/p' <<< "$out" | head -1)
    # a bounded search (--depth, --datapath) says so; a proof's own port search does not make it one
    grep -q "proved, unbounded" <<< "$out" || { grep -q "no property fails within the first" <<< "$out" && verdict=$(sed -n 's/.*\(no property fails within the first [0-9]* clock edges\).*/bounded: \1/p' <<< "$out" | head -1); }
    e=$(date +%s.%N)
    [ -n "$verdict" ] || verdict="error: $(tail -1 <<< "$out")"
    printf '| %s | %s | %.1f |\n' "$what" "$verdict" "$(awk -v a="$s" -v b="$e" 'BEGIN { print b - a }')" >> "$rows"
    echo "done: $what: $verdict" >&2
}
for s in 0 3 13; do
    $bin generate --out "$work/v$s" --stages "$s" >/dev/null 2>&1
    row "valid edge, lean, $s stages" $bin prove --rtl "$work/v$s" --time-limit "$limit"
done
$bin generate --out "$work/pl" --cos-frac-bits 6 --n-bits 4 --color-bits 5 --intensity-frac-bits 6 --stages 3 >/dev/null 2>&1
row "pipelining, lean 6/4/5/6 bits, 3 stages" $bin prove --pipelining --rtl "$work/pl" --time-limit "$limit"
$bin generate --out "$work/pl8" --cos-frac-bits 8 --n-bits 5 --color-bits 6 --intensity-frac-bits 8 --stages 10 >/dev/null 2>&1
row "pipelining, lean 8/5/6/8 bits, 10 stages" $bin prove --pipelining --rtl "$work/pl8" --time-limit "$limit"
$bin generate --out "$work/pf" --model fitted --cos-frac-bits 8 --n-bits 5 --color-bits 6 --intensity-frac-bits 8 --stages 4 >/dev/null 2>&1
row "pipelining, fitted 8/5/6/8 bits, 4 stages" $bin prove --pipelining --rtl "$work/pf" --time-limit "$limit"
# the delivered values against the valid twin (prove --datapath), narrow and at default widths
$bin generate --out "$work/dn" --interface ready --colour static --clock-enable --tag-bits 2 --cos-frac-bits 6 --n-bits 4 --color-bits 3 --intensity-frac-bits 5 --stages 2 >/dev/null 2>&1
row "datapath, ready 6/4/3/5 bits, 2 stages, static colour, clock enable" $bin prove --datapath --rtl "$work/dn" --time-limit "$limit"
$bin generate --out "$work/da" --interface axis --tlast --tag-bits 1 --clock-enable --colour static --cos-frac-bits 8 --n-bits 4 --color-bits 4 --intensity-frac-bits 6 --stages 5 >/dev/null 2>&1
row "datapath, axis 8/4/4/6 bits, 5 stages, tlast, static colour, clock enable" $bin prove --datapath --rtl "$work/da" --time-limit "$limit"
# at default widths, where delay lines wait in RAM (<top>_delay_ram: its contract proved
# alone first); then that module with its read address one place off
# each model at its deepest (not a number written here: a datapath that changes its depth
# changes the row, rather than stopping the bench)
lean=$(max_stages); $bin generate --out "$work/pd" --stages "$lean" >/dev/null 2>&1
row "pipelining, lean default widths, $lean stages (1 delay line in RAM)" $bin prove --pipelining --rtl "$work/pd" --time-limit "$limit"
s=$(max_stages --model fitted); $bin generate --out "$work/pfd" --model fitted --stages "$s" >/dev/null 2>&1
row "pipelining, fitted default widths, $s stages (8 delay lines in RAM, 5 contracts)" $bin prove --pipelining --rtl "$work/pfd" --time-limit "$limit"
s=$(max_stages --model blinn); $bin generate --out "$work/pbd" --model blinn --stages "$s" >/dev/null 2>&1
row "pipelining, blinn default widths, $s stages (2 delay lines in RAM)" $bin prove --pipelining --rtl "$work/pbd" --time-limit "$limit"
s=$(max_stages --model schlick); $bin generate --out "$work/psd" --model schlick --stages "$s" >/dev/null 2>&1
row "pipelining, schlick default widths, $s stages (1 delay line in RAM)" $bin prove --pipelining --rtl "$work/psd" --time-limit "$limit"
cp -r "$work/pd" "$work/pdx"
sed -i 's/^localparam integer NEXT_FROM_I = (1 << ABITS) + 1 - TRAIL_PLACES;/localparam integer NEXT_FROM_I = (1 << ABITS) + 2 - TRAIL_PLACES;/' "$work/pdx/specular_unit_delay_ram.v"
row "pipelining, lean default widths, $lean stages, the delay RAM's read address one place off" $bin prove --pipelining --edited --rtl "$work/pdx" --time-limit "$limit"
# the handshake at default widths: ready with a tag, axis with a tag, a clock enable and a
# static colour, at three depths; then each fault on a ready unit
for s in 0 3 13; do
    $bin generate --out "$work/r$s" --interface ready --stages "$s" --tag-bits 12 >/dev/null 2>&1
    row "ready edge, lean, $s stages, 12-bit tag" $bin prove --rtl "$work/r$s" --time-limit "$limit"
    $bin generate --out "$work/a$s" --interface axis --stages "$s" --tag-bits 8 --clock-enable --colour static >/dev/null 2>&1
    row "axis edge, lean, $s stages, 8-bit tag, clock enable, static colour" $bin prove --rtl "$work/a$s" --time-limit "$limit"
done
$bin generate --out "$work/r" --interface ready --stages 5 --tag-bits 12 >/dev/null 2>&1
row "ready edge, lean, 5 stages, 12-bit tag" $bin prove --rtl "$work/r" --time-limit "$limit"
buffer=specular_unit_out_buffer.v
# broken UNIT NAME FILE FROM TO: a copy of $work/UNIT as $work/NAME with FROM replaced by TO in
# FILE (once); with DELETE=1 the buffer's own assertions deleted first
broken() {
    local d="$work/$2"
    cp -r "$work/$1" "$d"
    FROM=$4 TO=$5 python3 scripts/py/prove_edit_buffer.py "$d/$3" "$d/$buffer"
}
fault() { # name file from to
    broken r "f-$1" "$2" "$3" "$4"
    row "ready edge, fault \`$1\`, a bounded search of 24 edges" $bin prove --rtl "$work/f-$1" --edited --depth 24 --time-limit "$limit"
}
fault dropped "$buffer" "leaving = count != 2'd0 && ready;" "leaving = count != 2'd0;"
fault unstable "$buffer" "if (held_copy == 2'd0 || out_ready) out[HI:LO] <=" "if (1'b1) out[HI:LO] <="
fault duplicated "$buffer" "read_at      <= advance(read, read_at);" "read_at <= advance(read && read_at != 5, read_at);"
fault queue_overrun "$buffer" "queue_full <= !out_ready && (queue_full || (queue_two && read));" "queue_full <= 1'b0;"
fault thermometer "$buffer" "else     stored_at_least[k] <= stored_level[k + 1] || (stored_level[k - 1] && grows_or_holds);" \
    "else     stored_at_least[k] <= k == 2 ? 1'b0 : stored_level[k + 1] || (stored_level[k - 1] && grows_or_holds);"
tag=$(grep -o 'tag_line\[[0-9]*:[0-9]*\];' "$work/r/specular_unit.v" | tail -1 | tr -d ';')
hi=${tag#tag_line[}; hi=${hi%%:*}; lo=${tag#*:}; lo=${lo%]}
fault tag_off specular_unit.v "= $tag;" "= tag_line[$((hi - 12)):$((lo - 12))];"
fault overfull "$buffer" "in_ready <= over_credits[DEPTH_LOG2];" "in_ready <= over_credits[DEPTH_LOG2] || over_credits == 0;"
# the outside audit's classes, each against the default proof (no --depth): the port
# checker's verdict, the colour check with a static colour
outside() { # unit name file from to
    broken "$1" "o-$2" "$3" "$4" "$5"
    row "$1 at default widths, outside class \`$2\`, the default proof" $bin prove --rtl "$work/o-$2" --edited --time-limit "$limit"
}
$bin generate --out "$work/axis3" --interface axis --stages 3 --tag-bits 1 --tlast --clock-enable --colour static >/dev/null 2>&1
outside axis3 colour_at_disabled_edge specular_unit.v "if (ks_load && aclken)" "if (ks_load)"
outside axis3 input_enable_ignored specular_unit.v "in_valid  = s_axis_tvalid & aclken;" "in_valid  = s_axis_tvalid;"
outside axis3 output_enable_ignored specular_unit.v "out_ready = m_axis_tready & aclken;" "out_ready = m_axis_tready;"
outside axis3 tlast_tuser_swapped specular_unit.v "assign {m_axis_tlast, m_axis_tuser} = out_tag;" "assign {m_axis_tuser, m_axis_tlast} = out_tag;"
read_line="wire                  read = (read_valid ? stored_at_least[2] : stored_at_least[1]) && !queue_full;"
DELETE=1 outside r never_reads "$buffer" "$read_line" "wire                  read = 1'b0;"
DELETE=1 outside r pairs_only "$buffer" "$read_line" "wire                  read = stored_at_least[2] && !queue_full;"
DELETE=1 outside r ignores_in_ready "$buffer" "assign take = in_valid && in_ready;" "assign take = in_valid;"
# a deadlock after the 40th pixel, past the bounded search and the covers, with every assertion
# of the unit neutered (as many as specgen writes, each empty): must not be proved
NEUTER=1 outside r deadlock_after_40_neutered "$buffer" "$read_line" \
    "reg [5:0] taken_count = 6'd0; always @(posedge clk) if (take && taken_count != 6'd63) taken_count <= taken_count + 1'b1; wire read = (read_valid ? stored_at_least[2] : stored_at_least[1]) && !queue_full && taken_count < 6'd40;"
{
    echo "# What \`specgen prove\` proves"
    echo
    echo "Generated by \`scripts/bench_prove.sh\` ($($bin --version 2>/dev/null || echo specgen); $(yosys -V | sed 's/ (.*//'), Debian's yosys-abc;"
    echo "time limit $limit s a proof). \"proved\" is unbounded (ABC pdr for the valid edge; for ready/axis k-induction with yosys"
    echo "sat over the port checker's properties, written from the manifest, and the unit's own assertions, its lemmas fed the"
    echo "checker's state, the datapath cut; for pipelining ABC iprove over the unrolled miter from any"
    echo "state and from power-up, each delay RAM's contract first proved alone by k-induction with yosys sat);"
    echo "\"refuted\" comes with a counterexample VCD; \"undecided\""
    echo "is neither (never reported as proved; out of time is the guard, not a verdict); \"bounded\" is a bounded search of the depth"
    echo "stated (\`--datapath\`: every delivered result against the unit's valid twin), not a proof. A ready/axis \"proved\" has also"
    echo "passed the port checker's bounded search (latency + 8 edges) and reached its covers. The faults are the simulation suite's own"
    echo "(tests/suite/interfaces.rs), applied to a ready unit of 5 stages with a 12-bit tag. The outside classes are broken units"
    echo "of the kinds the outside set holds, at default widths against the default proof (no --depth; the buffer's own"
    echo "assertions deleted where the class says so): each must be refuted, or (neutered assertions) left undecided."
    echo
    echo "| proof | verdict | seconds |"
    echo "|---|---|---|"
    cat "$rows"
} > benchmarks/prove.md
bench_stamp "scripts/bench_prove.sh" >> benchmarks/prove.md
echo "wrote benchmarks/prove.md" >&2
