#!/bin/bash
# Coverage of shockfit's 95% interval over independent granular runs
# (docs/shockfit.md, "Interval coverage"). For each seed: granular run, then
# shockfit with the averaging groups' interval and with the bootstrap over
# stations (--groups none). Prints one line per run and the summary: mean,
# sd, 1.96 sd, median half-width and coverage of both intervals.
#   bench/coverage/coverage.sh SCENE_TEMPLATE.yaml.in OUTDIR [SEED ...]
# (a scene with SEED where granular.seed goes: bench/coverage/*.yaml.in)
# SEED defaults to the odd seeds 1..23 (a run of seed N uses N and N+1 for
# its two replicas, so neighbouring seeds would share one). Run from the
# repository root after the build; CPU seconds from /usr/bin/time.
# REFIT=1 keeps a seed's recorded granular run (OUTDIR/sSEED/g) and refits it
# with the current shockfit (runs.txt and summary.txt start afresh).
set -euo pipefail
template=$1; out=$2; shift 2
seeds=("$@"); [ ${#seeds[@]} -gt 0 ] || seeds=(1 3 5 7 9 11 13 15 17 19 21 23)
bin=${BIN:-build/bin}
mkdir -p "$out"
[ "${REFIT:-0}" = 1 ] && rm -f "$out/runs.txt"
source "$(dirname "$0")/../json_value.sh"
for s in "${seeds[@]}"; do
  d="$out/s$s"; mkdir -p "$d"
  sed "s/SEED/$s/" "$template" > "$d/scene.yaml"
  if [ "${REFIT:-0}" != 1 ] || [ ! -f "$d/g/fields.vti" ]; then
    CI=1 /usr/bin/time -f "%U" -o "$d/cpu.txt" "$bin/granular" run "$d/scene.yaml" --out "$d/g" > /dev/null 2> "$d/err.txt"
  fi
  "$bin/shockfit" "$d/scene.yaml" --fields "$d/g/fields.vti" --out "$d/s" > /dev/null 2>> "$d/err.txt"
  "$bin/shockfit" "$d/scene.yaml" --fields "$d/g/fields.vti" --groups none --out "$d/sb" > /dev/null 2>> "$d/err.txt"
  kind=$(value "$d/s/summary.json" shock | tr -d '"')
  if [ "$kind" = attached ]; then key=shock_angle_deg; ci=shock_angle_ci_deg; else key=standoff; ci=standoff_ci; fi
  echo "$s $kind $(value "$d/s/summary.json" $key) $(value "$d/s/summary.json" $ci) $(value "$d/sb/summary.json" $ci) $(cat "$d/cpu.txt")" | tee -a "$out/runs.txt"
done
awk '$2 != "none" && $3 != "null" { n++; v[n] = $3; g[n] = $4; b[n] = $5; c[n] = $6 }
  function median(a, m,   i, j, t, x) { for (i = 1; i <= m; i++) x[i] = a[i];
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (x[j] < x[i]) { t = x[i]; x[i] = x[j]; x[j] = t }
    return m % 2 ? x[(m + 1) / 2] : (x[m / 2] + x[m / 2 + 1]) / 2 }
  END { for (i = 1; i <= n; i++) s += v[i]; mean = s / n
        for (i = 1; i <= n; i++) { ss += (v[i] - mean) ^ 2; cg += ((v[i] - mean) ^ 2 <= g[i] ^ 2); cb += ((v[i] - mean) ^ 2 <= b[i] ^ 2) }
        sd = sqrt(ss / (n - 1))
        printf "%d runs: mean %.4f sd %.4f 1.96 sd %.4f | groups: median half-width %.4f coverage %.2f | bootstrap: median half-width %.4f coverage %.2f | granular CPU s median %.1f\n",
               n, mean, sd, 1.96 * sd, median(g, n), cg / n, median(b, n), cb / n, median(c, n) }' "$out/runs.txt" | tee "$out/summary.txt"
