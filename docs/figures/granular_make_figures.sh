#!/usr/bin/env bash
# Reproduces every figure of docs/granular_flow.md (validation report).
# usage: docs/figures/granular_make_figures.sh [BUILD_DIR [PART...]]
#   BUILD_DIR default build; PART: fields perturbation box (default: all)
# Needs: build/bin/granular, python3, gnuplot. Runtime ~5 min on 2 cores.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$ROOT/build}/bin/granular
FIG=$ROOT/docs/figures
WORK=$(mktemp -d /tmp/granular_figures.XXXX)
export CI=true  # plain logs
PARTS=${*:2}
PARTS=${PARTS:-fields perturbation box}
want() { [[ " $PARTS " == *" $1 "* ]]; }

# 1. Volume fraction of the wedge and disc cases (default parameters).
want fields || want perturbation && for c in wedge_M3_10 disc_M4; do
  want fields || [ $c = wedge_M3_10 ] || continue
  "$BIN" run "$ROOT/pipeline/cases/$c.yaml" --out "$WORK/$c" --np 2
  python3 "$FIG/granular_field_png.py" "$WORK/$c/fields.vti" volume_fraction "$FIG/granular_${c}_volume_fraction.png" \
    "$c: granular volume fraction (time average, 2 replicas)"
done

# 2. Sensitivity to a tiny perturbation of the initial state: the same
#    scene with the inflow speed (so every initial velocity) changed by 1e-12.
if want perturbation; then
cat > "$WORK/pert.yaml" <<'YAML'
name: wedge_M3_10_perturbed
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {mach: 3.000000000003}
YAML
"$BIN" run "$WORK/pert.yaml" --out "$WORK/pert" --np 2
python3 "$FIG/granular_perturbation.py" "$WORK/wedge_M3_10/fields.vti" "$WORK/pert/fields.vti" \
  "$FIG/granular_perturbation_volume_fraction.png" | tee "$FIG/granular_perturbation.txt"
fi

# 3. Energy change and overlap recoveries per collision in periodic boxes
#    over volume fractions and restitution coefficients (2000 disks). The
#    box starts from a lattice; the first collisions are atypical (the
#    fastest approaches collide first), so each case runs twice with the same
#    seed, to C1 = 2N and to C2 = C1 + K collisions, and the loss is measured
#    on the window between them (the runs are deterministic).
if want box; then
CSV=$FIG/granular_energy_per_collision.csv
echo "nu,e,particles,window_collisions,energy_c1,energy_c2,recoveries,loss_per_collision_over_T,expected" > "$CSV"
for e in 1.0 0.95 0.8 0.5; do
  for nu in 0.05 0.1 0.2 0.3 0.4 0.5 0.6; do
    W=$(python3 -c "import math; print(round(math.sqrt(2000*math.pi/4/$nu), 6))")
    C1=4000
    C2=$(python3 -c "print(4000 + int(2000*(4 if $e == 1.0 else 1.0/(1-$e*$e))))")
    for C in $C1 $C2; do
      printf 'box: {width: %s, height: %s, periodic: true}\ngranular: {packing_fraction: %s, restitution: %s, seed: 1, collisions: %s}\n' \
        "$W" "$W" "$nu" "$e" "$C" > "$WORK/box.yaml"
      "$BIN" run "$WORK/box.yaml" --out "$WORK/box_$C" > /dev/null
    done
    python3 - "$WORK/box_$C1/summary.json" "$WORK/box_$C2/summary.json" "$nu" "$e" >> "$CSV" <<'PY'
import json, math, sys
a, b = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
nu, e = float(sys.argv[3]), float(sys.argv[4])
n, c = b['particles'], b['collisions'] - a['collisions']
e1, e2 = a['energy_final'], b['energy_final']
# E = N T in 2D; dE per collision = -(1 - e^2) T under molecular chaos, so
# ln(E2/E1) = -(1 - e^2) C / N over the window.
loss = -n * math.log(e2 / e1) / c
print(f"{nu},{e},{n},{c},{e1!r},{e2!r},{b['recoveries']},{loss!r},{1 - e * e!r}")
PY
  done
done
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 800,500
set output '$FIG/granular_energy_per_collision.png'
set title 'Energy lost per collision / T  vs volume fraction (dashed: 1 - e^2)'
set xlabel 'volume fraction'; set ylabel '-(N/C) ln(E_2/E_1)'
set key outside
set yrange [-0.05:1.0]
plot for [e in "0.95 0.8 0.5"] '$CSV' using (\$2==e+0 ? \$1 : 1/0):8 with linespoints title 'e = '.e, \
     for [e in "0.95 0.8 0.5"] (1 - (e+0)**2) with lines dt 2 notitle
set output '$FIG/granular_energy_elastic.png'
set title 'Elastic (e = 1): relative energy change per collision'
set ylabel '|E_2 - E_1| / E_1 / C'; set logscale y; set yrange [1e-22:1e-12]; set format y '%.0e'
plot '$CSV' using (\$2==1 ? \$1 : 1/0):(abs(\$6-\$5)/\$5/\$4 + 1e-21) with linespoints title 'e = 1 (1e-21 added: exact zeros)'
unset logscale y; set format y '%g'
set output '$FIG/granular_recoveries_per_collision.png'
set title 'Overlap recoveries (pass-throughs) per collision (expected 0)'
set ylabel 'recoveries / collisions'; set yrange [-1e-6:1e-5]
plot for [e in "1.0 0.95 0.8 0.5"] '$CSV' using (\$2==e+0 ? \$1 : 1/0):(\$7/\$4) with linespoints title 'e = '.e
GP
fi
echo "figures in $FIG (work files in $WORK)"
