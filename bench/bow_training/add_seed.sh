#!/bin/bash
# Another granular seed of a finished blunt training run, sharing its gas grid:
# a training body's shock from a few runs scatters by several percent at low
# Mach numbers (docs/calibration.md, "More seeds per training body"), and the
# gas shock does not depend on the granular seed, so only the granular and
# shockfit stages are rerun. Writes OUTDIR as `pipeline calibrate
# --bow-shock-runs` reads a run: the source's scene (seed replaced), its
# uniform grids (cfd/uniform_*), and granular/ + shockfit/ of the new seed; the
# summary's prediction CPU seconds become the new run's and its grids' CPU
# seconds 0 (they are charged once, with the source run).
#   bench/bow_training/add_seed.sh RUNDIR SEED OUTDIR
# Run from the repository root after the build.
set -euo pipefail
src=$1; seed=$2; out=$3
bin=${BIN:-build/bin}
[ -f "$src/summary.json" ] && [ -f "$src/scene.resolved.yaml" ] ||
  { echo "add_seed.sh: $src: not a finished pipeline run (summary.json, scene.resolved.yaml)" >&2; exit 2; }
case "$seed" in '' | *[!0-9]*) echo "add_seed.sh: seed '$seed': expected a whole number" >&2; exit 2 ;; esac
mkdir -p "$out/cfd"
for g in "$src"/cfd/uniform_*; do
  mkdir -p "$out/cfd/$(basename "$g")"
  cp -r "$g/shockfit" "$g/history.csv" "$out/cfd/$(basename "$g")/"
done
# The granular block's seed only (shockfit's bootstrap seed stays, as in `pipeline
# run`); the resolved domain is left out, so that the stream is sized from the
# body as the run's was (a domain given is simulated as given, without the
# inflow reach the default adds).
awk -v seed="$seed" '/^[a-z]/ { block = $1 } block == "domain:" { next }
  block == "granular:" && /^  seed: / { $0 = "  seed: " seed } { print }' \
  "$src/scene.resolved.yaml" > "$out/scene.resolved.yaml"
CI=1 "$bin/granular" run "$out/scene.resolved.yaml" --out "$out/granular" > "$out/granular.log"
CI=1 "$bin/shockfit" "$out/scene.resolved.yaml" --fields "$out/granular/fields.vti" \
  --out "$out/shockfit" > "$out/shockfit.log"
python3 - "$src/summary.json" "$out/granular/summary.json" "$out/summary.json" <<'EOF'
import json, sys
run = json.load(open(sys.argv[1]))
granular = json.load(open(sys.argv[2]))
run["prediction"]["cpu_seconds"] = granular["cpu_seconds"]
run["prediction"]["note"] = "granular and shockfit rerun at another seed; the gas grids are the source run's"
for r in run.get("runs", []):
    # The grids are the source run's: charged there, not again here.
    r["cpu_seconds"] = 0.0
    r["mesh_cpu_seconds"] = 0.0
    r["note"] = "the source run's grid; its CPU is charged with that run"
json.dump(run, open(sys.argv[3], "w"), indent=2)
EOF
