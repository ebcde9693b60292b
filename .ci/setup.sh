#!/usr/bin/env bash
# One-stop set-up for a fresh Debian 12 machine: installs the Debian packages
# the project needs (skipping those already installed), configures and builds
# with CMake, then does what the first argument asks:
#   main   run the pipeline on the built-in wedge M3/10 scene (out/wedge_M3_10)
#   test   run the whole test suite (ctest)
#   build  stop after building
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  openfoam                      # rhoCentralFoam, gmshToFoam, checkMesh, decomposePar (ESI v1912)
  libgmsh-dev                   # gmsh 4.8 C++ API
  libcgal-dev libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin    # replicas as MPI ranks; parallel OpenFOAM runs
  gnuplot-nox                   # PNG figures
  python3-vtk9                  # interop test: outputs read by VTK's own readers (what ParaView uses)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

JOBS=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$JOBS"

case "${1:-build}" in
  main)
    exec build/bin/pipeline run pipeline/cases/wedge_M3_10.yaml --out out/wedge_M3_10 "${@:2}"
    ;;
  test)
    cd build
    # OpenFOAM and gmsh tests use their own temporary case directories, so
    # tests may run two at a time on the 2-core CI machine.
    exec ctest --output-on-failure -j 2 "${@:2}"
    ;;
  build) ;;
  *)
    echo "usage: .ci/setup.sh [main|test|build] [extra args]" >&2
    exit 2
    ;;
esac
