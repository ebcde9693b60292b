#!/bin/bash
# Kurganov's and Tadmor's fluxes from the impulsive start (bodies at rest):
# for each Mach number, a uniform meshgen grid of cell size H (body lengths),
# then `cfd run` for 3 flow-throughs with each flux named and the fallback
# off. One line per run: scene, cells, flux, exit code (1: diverged).
# docs/reliability.md, "The flux from an impulsive start".
#
#   bench/flux_start/sweep.sh OUT disc|apollo H MACH...
#   e.g. for h in 0.2 0.1 0.05 0.025; do bench/flux_start/sweep.sh out/flux apollo $h 3 4 5 6 7; done
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$1 body=$2 h=$3
shift 3
case $body in
  disc) spec="{kind: disc, radius: 0.5}" ;;
  apollo) spec="{kind: apollo, diameter: 1.0}" ;;
  *) echo "sweep.sh: body must be disc or apollo" >&2; exit 2 ;;
esac
mkdir -p "$out"
for mach in "$@"; do
  tag="${body}_M${mach}_h${h}"
  for flux in Kurganov Tadmor; do
    printf 'name: %s\nbody: %s\nfreestream: {mach: %s}\ncfd: {end_time: 3, fallback: false, flux_scheme: %s}\n' \
      "$tag" "$spec" "$mach" "$flux" > "$out/$tag.$flux.yaml"
  done
  [ -d "$out/mesh_$tag" ] || "$root/build/bin/meshgen" "$out/$tag.Kurganov.yaml" --uniform --h-min "$h" \
    --out "$out/mesh_$tag" > "$out/log.mesh_$tag" 2>&1
  cells=$(grep -o '"cells": [0-9]*' "$out/mesh_$tag/summary.json" | grep -o '[0-9]*$')
  for flux in Kurganov Tadmor; do
    rm -rf "$out/case_$tag.$flux" "$out/case_$tag.$flux.failed"
    "$root/build/bin/cfd" run "$out/$tag.$flux.yaml" --mesh "$out/mesh_$tag" --out "$out/case_$tag.$flux" \
      > "$out/log.$tag.$flux" 2>&1
    echo "$tag cells $cells $flux exit $?"
  done
done
