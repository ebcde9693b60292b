#!/usr/bin/env bash
# Makes a granular fields.vti and a small finished rhoCentralFoam case, then
# reads both with VTK's readers (vtk_readers.py checks arrays and patches).
set -euo pipefail
bin="$1"; src="$2"; py="$3"
work="$(mktemp -d "${TMPDIR:-/tmp}/shockgrain_interop.XXXXXX")"
trap 'rm -rf "$work"' EXIT
scene="$src/tests/data/wedge_small.yaml"
"$bin/granular" run "$scene" --out "$work/granular" > "$work/granular.log" 2>&1
"$bin/cfd" blockmesh "$scene" --cells 1500 --out "$work/mesh" > "$work/mesh.log" 2>&1
"$bin/cfd" run "$scene" --mesh "$work/mesh" --out "$work/case" > "$work/case.log" 2>&1
"$py" "$src/tests/interop/vtk_readers.py" "$work/granular/fields.vti" "$work/case"
