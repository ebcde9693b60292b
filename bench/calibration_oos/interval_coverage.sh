#!/bin/bash
# Seed-to-seed coverage of shockfit's 95% angle interval on the runs of one
# or more `angle_check.sh` output directories (docs/shockfit.md, "The groups'
# own fits"): per wedge, the mean angle over its seeds stands in for the
# truth; a run is covered when |angle - mean| <= half-width x sqrt((n-1)/n)
# (the mean of n runs includes the run itself). Wedges with one run are
# skipped. Prints the covered runs, the fraction and the median half-width.
#   bench/calibration_oos/interval_coverage.sh OUTDIR...
set -euo pipefail
[ $# -gt 0 ] || { echo "usage: $0 ANGLE_CHECK_OUTDIR..." >&2; exit 2; }
for d in "$@"; do
  [ -f "$d/runs.txt" ] || { echo "$d/runs.txt: not found (run angle_check.sh first)" >&2; exit 2; }
done
# runs.txt: wedge seed e angle half-width gas error class
for d in "$@"; do awk -v set="$d" '{ print set "/" $1, $4, $5 }' "$d/runs.txt"; done |
  awk '{ key[NR] = $1; a[NR] = $2; h[NR] = $3; n[$1]++; s[$1] += $2 }
       END { for (i = 1; i <= NR; i++) { k = key[i]; if (n[k] < 2) continue
               m = s[k] / n[k]; runs++; hw[runs] = h[i]
               if ((a[i] - m) ^ 2 <= h[i] ^ 2 * (n[k] - 1) / n[k]) covered++ }
             if (!runs) { print "no wedge with two or more runs"; exit 1 }
             for (i = 1; i <= runs; i++) for (j = i + 1; j <= runs; j++) if (hw[j] < hw[i]) { t = hw[i]; hw[i] = hw[j]; hw[j] = t }
             med = runs % 2 ? hw[(runs + 1) / 2] : (hw[runs / 2] + hw[runs / 2 + 1]) / 2
             printf "%d of %d runs covered (%.2f); median half-width %.2f deg\n", covered, runs, covered / runs, med }'
