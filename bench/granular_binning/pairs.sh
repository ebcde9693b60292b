#!/bin/bash
# Two builds of `granular` side by side: the same scene and seed at once,
# one per core, cores swapped each round; prints one line per pair (user
# and system CPU s, wall s of each, whether fields.vti and groups.vti are
# byte-identical) and keeps the runs under OUT.
#   bench/granular_binning/pairs.sh OLD_BIN/granular NEW_BIN/granular OUT [ROUNDS]
set -euo pipefail
old=$1 new=$2 out=$3 rounds=${4:-7}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
for r in $(seq 1 "$rounds"); do
  for scene in "$here"/wedge_*.yaml; do
    s=$(basename "$scene" .yaml)
    if ((r % 2)); then c_old=0 c_new=1; else c_old=1 c_new=0; fi
    rm -rf "$out/old_${s}_$r" "$out/new_${s}_$r"
    (CI=1 taskset -c $c_old /usr/bin/time -f "%U %S %e" "$old" run "$scene" --out "$out/old_${s}_$r" --np 1 \
      > /dev/null 2> "$out/time_old_${s}_$r.txt") &
    (CI=1 taskset -c $c_new /usr/bin/time -f "%U %S %e" "$new" run "$scene" --out "$out/new_${s}_$r" --np 1 \
      > /dev/null 2> "$out/time_new_${s}_$r.txt") &
    wait
    same=DIFFER
    if cmp -s "$out/old_${s}_$r/fields.vti" "$out/new_${s}_$r/fields.vti" &&
      cmp -s "$out/old_${s}_$r/groups.vti" "$out/new_${s}_$r/groups.vti"; then same=identical; fi
    echo "$r $s old $(tail -1 "$out/time_old_${s}_$r.txt") new $(tail -1 "$out/time_new_${s}_$r.txt") $same"
  done
done
