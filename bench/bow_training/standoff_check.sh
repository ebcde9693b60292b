#!/bin/bash
# A blunt body's granular standoff against a gas standoff, over seeds: the
# out-of-sample check of a blunt shape's restitution (docs/calibration.md,
# "Discs with the stagnation-line reference"). For each seed, `pipeline
# predict --predictor granular` on the scene with that seed, then one line:
# seed, restitution, standoff, its 95% half-width, relative error; and the
# mean's error. Body lengths throughout (shockfit's standoff).
#   bench/bow_training/standoff_check.sh SCENE.yaml GAS_STANDOFF TABLE OUTDIR SEED...
# With E=e in the environment the runs take that restitution instead of the
# table's; with GAS_CSV=the gas's shock.csv (shockfit on a uniform grid of the
# same body) each line adds the stations accepted in both, their mean and RMS
# relative error (station_errors.py). The standoff is the prediction's (after
# a table's station bias, where the table has one for the body's shape).
# Run from the repository root after the build.
set -euo pipefail
scene=$1; gas=$2; table=$3; out=$4; shift 4
bin=${BIN:-build/bin}
mkdir -p "$out"
source "$(dirname "$0")/../json_value.sh"
# Written aside and moved in at the end: a stopped or failed rerun leaves the
# last finished runs.txt / summary.txt in place.
: > "$out/runs.txt.part"
for s in "$@"; do
  d="$out/seed$s"; mkdir -p "$d"
  extra=""; [ -z "${E:-}" ] || extra=", restitution: $E"
  { cat "$scene"; printf '\ngranular: {seed: %s%s}\n' "$s" "$extra"; } > "$d/scene.yaml"
  CI=1 "$bin/pipeline" predict "$d/scene.yaml" --predictor granular --calibration "$table" \
    --out "$d/p" > "$d/predict.json" 2> "$d/err.txt"
  e=$(value "$d/p/granular/summary.json" restitution)
  st=$(value "$d/p/summary.json" standoff); ci=$(value "$d/p/summary.json" standoff_ci)
  stations=""
  [ -z "${GAS_CSV:-}" ] || stations=" $(python3 "$(dirname "$0")/station_errors.py" "$d/p/shock.csv" "$GAS_CSV")"
  echo "$s $e $st $ci $(awk -v a="$st" -v g="$gas" 'BEGIN { printf "%+.4f", a / g - 1 }')$stations" \
    | tee -a "$out/runs.txt.part"
done
awk -v g="$gas" '{ n++; s += $3 } END { printf "%d seeds: mean standoff %.4f against %.4f: %+.2f%%\n", n, s / n, g, 100 * (s / n / g - 1) }' \
  "$out/runs.txt.part" | tee "$out/summary.txt.part"
mv "$out/runs.txt.part" "$out/runs.txt"
mv "$out/summary.txt.part" "$out/summary.txt"
