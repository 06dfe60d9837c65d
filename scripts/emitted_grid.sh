#!/bin/bash
# The emitted files' hashes over a grid: every model x family x interface x {tag, static colour,
# clock enable, active-low reset, tlast} x depths 0, 1, 3, 9. A refactoring of what is emitted
# (e.g. moving the unit's edge into templates) keeps them byte-identical:
#   scripts/emitted_grid.sh OLD_SPECGEN before.txt; scripts/emitted_grid.sh NEW_SPECGEN after.txt
#   diff before.txt after.txt
# usage: emitted_grid.sh SPECGEN OUTLIST
set -u
BIN=$1; OUT=$2; : > "$OUT"
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
W=$TMP/w
for m in quadratic schlick fitted blinn blinn-pow; do
 for t in generic ice40 ecp5 gowin; do
  for i in valid ready axis; do
   for opts in "" "--tag-bits 3" "--tag-bits 1 --colour static" "--clock-enable --reset sync-low" "--tlast --tag-bits 2 --colour static --clock-enable"; do
    [ "$i" != axis ] && [[ "$opts" == *tlast* ]] && continue
    [ "$i" = valid ] && [[ "$opts" == *clock-enable* ]] && continue
    for s in 0 1 3 9; do
      rm -rf $W
      if "$BIN" generate --model $m --target $t --interface $i $opts --stages $s --n-bits 6 --out $W >/dev/null 2>$TMP/err; then
        (cd $W && find . -type f | sort | xargs sha256sum | sed "s/^/$m $t $i [$opts] $s /") >> "$OUT"
      else echo "$m $t $i [$opts] $s ERR $(head -c 100 $TMP/err)" >> "$OUT"; fi
    done
   done
  done
 done
done
