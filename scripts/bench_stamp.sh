# Sourced by the bench scripts.
# The provenance line that ends every benchmark file: the command that wrote it, the date, the
# commit (and whether the sources had changes beside it) and the machine.
bench_stamp() {
    local dirty=""
    git diff --quiet HEAD -- src templates data 2>/dev/null || dirty=" with uncommitted changes"
    printf '\n_Written by `%s` on %s at commit %s%s, on %s cores %s (%s)._\n' "$*" "$(date -u +%F)" "$(git rev-parse --short HEAD)" "$dirty" "$(nproc)" "$(uname -m)" "$(uname -sr)"
}
