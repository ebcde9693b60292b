#!/bin/bash
# Wedges that are neither training points nor case studies, run through the
# granular predictor with a calibration table: the out-of-sample angle check
# of docs/calibration.md. For each wedge and seed, `pipeline predict
# --predictor granular`, the gas angle from `pipeline predict --predictor
# correlation` (theta-beta-Mach for an attached wedge), then one line:
# wedge, seed, e, granular angle, its 95% half-width, gas angle, error (deg),
# class. Last, the RMS, max and mean error per class: wedges inside the
# training ranges, the wedge case studies (never fitted; generated here with
# their Mach number and deflection, every other key at its default as in
# pipeline/cases) and wedges outside the training ranges.
#   bench/calibration_oos/angle_check.sh TABLE OUTDIR SEED...
# With EXTRA='YAML LINES' in the environment every scene gets those lines too
# (e.g. EXTRA='shockfit: {field: v}' for a table calibrated on that field);
# WEDGES='MACH ANGLE CLASS' lines replace the wedge list below; GRANULAR='KEY: VALUE, ...'
# joins the seed in each run's granular block (e.g. GRANULAR='averaging: 8').
# Run from the repository root after the build.
set -euo pipefail
table=$1; out=$2; shift 2
bin=${BIN:-build/bin}
mkdir -p "$out"
source "$(dirname "$0")/../json_value.sh"
# mach angle class: 1 inside the training ranges (Mach 2.5-6, 8-26 deg),
# 2 a case study, 0 outside the training ranges
default_wedges="2.8 11 1
3.2 18 1
4.5 12 1
5.0 10 1
5.5 17 1
3.0 10 2
4.0 15 2
5.0 20 2
2.2 9 0
3.8 6 0
4.0 22 1
3.5 30 0"
wedges=${WEDGES:-$default_wedges}
# Written aside and moved in at the end: a stopped or failed rerun leaves the
# last finished runs.txt / summary.txt in place.
: > "$out/runs.txt.part"
while read -r m a in; do
  name="oos_M${m}_${a}"
  d="$out/$name"; mkdir -p "$d"
  printf 'name: %s\nbody: {kind: wedge, angle_deg: %s, length: 1.0}\nfreestream: {mach: %s}\n' \
    "$name" "$a" "$m" > "$d/scene.yaml"
  [ -z "${EXTRA:-}" ] || printf '%s\n' "$EXTRA" >> "$d/scene.yaml"
  CI=1 "$bin/pipeline" predict "$d/scene.yaml" --predictor correlation --out "$d/gas" \
    > /dev/null 2> "$d/gas_err.txt"
  gas=$(value "$d/gas/summary.json" shock_angle_deg)
  for s in "$@"; do
    { cat "$d/scene.yaml"; printf 'granular: {seed: %s%s}\n' "$s" "${GRANULAR:+, $GRANULAR}"; } > "$d/seed$s.yaml"
    CI=1 "$bin/pipeline" predict "$d/seed$s.yaml" --predictor granular --calibration "$table" \
      --out "$d/seed$s" > /dev/null 2> "$d/seed${s}_err.txt"
    e=$(value "$d/seed$s/granular/summary.json" restitution)
    ang=$(value "$d/seed$s/summary.json" shock_angle_deg)
    ci=$(value "$d/seed$s/summary.json" shock_angle_ci_deg)
    echo "$name $s $e $ang $ci $gas $in" | awk '{ printf "%s %s %s %.2f %.2f %.2f %+.2f %s\n", $1, $2, $3, $4, $5, $6, $4 - $6, $7 }' \
      | tee -a "$out/runs.txt.part"
  done
done <<< "$wedges"
awk '{ k = $8; n[k]++; s[k] += $7; q[k] += $7 * $7; if ($7 * $7 > mx[k] * mx[k]) mx[k] = $7 }
     END { split("outside the training ranges|inside the training ranges|case studies", label, "|")
           for (k = 1; k <= 3; k++) { c = k % 3; if (n[c])
             printf "%s: %d runs, RMS %.2f deg, max |error| %.2f, mean %+.2f\n",
                    label[c + 1], n[c], sqrt(q[c] / n[c]), (mx[c] < 0 ? -mx[c] : mx[c]), s[c] / n[c] } }' \
  "$out/runs.txt.part" | tee "$out/summary.txt.part"
mv "$out/runs.txt.part" "$out/runs.txt"
mv "$out/summary.txt.part" "$out/summary.txt"
