#!/usr/bin/env bash
# Reproduces every figure of docs/granular_flow.md (validation report).
# usage: docs/figures/granular_make_figures.sh [BUILD_DIR]   (default: build)
# Needs: build/bin/granular, python3, gnuplot. Runtime ~5 min on 2 cores.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$ROOT/build}/bin/granular
FIG=$ROOT/docs/figures
WORK=$(mktemp -d /tmp/granular_figures.XXXX)
export CI=true  # plain logs

# 1. Volume fraction of the wedge and disc cases (default parameters).
for c in wedge_M3_10 disc_M4; do
  "$BIN" run "$ROOT/pipeline/cases/$c.yaml" --out "$WORK/$c" --np 2
  python3 "$FIG/granular_field_png.py" "$WORK/$c/fields.vti" volume_fraction "$FIG/granular_${c}_volume_fraction.png" \
    "$c: granular volume fraction (time average, 2 replicas)"
done

# 2. Sensitivity to a tiny perturbation of the initial state: the same
#    scene with the inflow speed (so every initial velocity) changed by 1e-12.
cat > "$WORK/pert.yaml" <<'YAML'
name: wedge_M3_10_perturbed
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {mach: 3.000000000003}
YAML
"$BIN" run "$WORK/pert.yaml" --out "$WORK/pert" --np 2
python3 "$FIG/granular_perturbation.py" "$WORK/wedge_M3_10/fields.vti" "$WORK/pert/fields.vti" \
  "$FIG/granular_perturbation_volume_fraction.png" | tee "$FIG/granular_perturbation.txt"

# 3. Energy change and overlap recoveries per collision in periodic boxes
#    over volume fractions and restitution coefficients (about 2000 disks).
CSV=$FIG/granular_energy_per_collision.csv
echo "nu,e,particles,collisions,energy_initial,energy_final,recoveries,loss_per_collision_over_T,expected" > "$CSV"
for e in 1.0 0.95 0.8 0.5; do
  for nu in 0.05 0.1 0.2 0.3 0.4 0.5 0.6; do
    W=$(python3 -c "import math; print(round(math.sqrt(2000*math.pi/4/$nu), 6))")
    C=$(python3 -c "print(int(2000*(4 if $e == 1.0 else 0.5/(1-$e*$e))))")
    printf 'box: {width: %s, height: %s, periodic: true}\ngranular: {packing_fraction: %s, restitution: %s, seed: 1, collisions: %s}\n' \
      "$W" "$W" "$nu" "$e" "$C" > "$WORK/box.yaml"
    "$BIN" run "$WORK/box.yaml" --out "$WORK/box" > /dev/null
    python3 - "$WORK/box/summary.json" "$nu" "$e" >> "$CSV" <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1])); nu, e = float(sys.argv[2]), float(sys.argv[3])
n, c, e0, e1 = j['particles'], j['collisions'], j['energy_initial'], j['energy_final']
# E = N T in 2D; dE per collision = -(1 - e^2) T under molecular chaos, so
# ln(E1/E0) = -(1 - e^2) C / N.
loss = -n * math.log(e1 / e0) / c
print(f"{nu},{e},{n},{c},{e0!r},{e1!r},{j['recoveries']},{loss!r},{1 - e * e!r}")
PY
  done
done
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 800,500
set output '$FIG/granular_energy_per_collision.png'
set title 'Energy lost per collision / T  vs volume fraction (lines: 1 - e^2)'
set xlabel 'volume fraction'; set ylabel '-(N/C) ln(E_1/E_0)'
set key outside
set yrange [-0.05:0.9]
plot for [e in "0.95 0.8 0.5"] '$CSV' using (\$2==e+0 ? \$1 : 1/0):8 with linespoints title 'e = '.e, \
     for [e in "0.95 0.8 0.5"] (1 - (e+0)**2) with lines dt 2 notitle
set output '$FIG/granular_energy_elastic.png'
set title 'Elastic (e = 1): relative energy change per collision'
set ylabel '|E_1 - E_0| / E_0 / C'; set logscale y; set yrange [*:*]; set format y '%.0e'
plot '$CSV' using (\$2==1 ? \$1 : 1/0):(abs(\$6-\$5)/\$5/\$4 + 1e-30) with linespoints title 'e = 1'
unset logscale y; set format y '%g'
set output '$FIG/granular_recoveries_per_collision.png'
set title 'Overlap recoveries (pass-throughs) per collision (expected 0)'
set ylabel 'recoveries / collisions'; set yrange [-1e-6:1e-5]
plot for [e in "1.0 0.95 0.8 0.5"] '$CSV' using (\$2==e+0 ? \$1 : 1/0):(\$7/\$4) with linespoints title 'e = '.e
GP
echo "figures in $FIG (work files in $WORK)"
