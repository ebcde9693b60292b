#!/usr/bin/env bash
# Cache misses per collision of the granular engine, counted by valgrind's
# cachegrind (a simulated cache, so the count is the same on any machine
# and does not move with the host's load, unlike the rates of granular_rate).
#
#   bench/cache_misses.sh [BUILD_DIR] [N]      (defaults: build, 200000)
#
# Runs build/bench/granular_rate under cachegrind with N disks for 1 and 3
# timed collisions per disk and prints the difference per collision: data
# misses of a 2 MiB last-level cache (one core's L2 on the benchmark
# machine; a system of N = 2e5 disks, ~25 MB, does not fit it) and of a
# 48 KiB L1. Software prefetches are not simulated: the count is what has to
# come from memory, whether or not it was asked for early. About 1 minute.
set -euo pipefail
build=${1:-build}
n=${2:-200000}
bin="$build/bench/granular_rate"
if ! command -v valgrind > /dev/null; then
  echo "cache_misses.sh: valgrind is not installed (apt-get install valgrind)" >&2
  exit 2
fi
if [[ ! -x $bin ]]; then
  echo "cache_misses.sh: $bin not found (cmake --build $build --target granular_rate)" >&2
  exit 2
fi

# Prints "LL_data_misses D1_data_misses" of one run.
misses() {
  valgrind --tool=cachegrind --cache-sim=yes --LL=2097152,16,64 --D1=49152,12,64 \
    --cachegrind-out-file=/dev/null "$bin" --repeats 1 "$n:$1" 2>&1 |
    awk '/LLd misses/ {gsub(",", "", $4); ll = $4} /D1  misses/ {gsub(",", "", $4); d1 = $4}
         END {print ll, d1}'
}

read -r ll1 d11 < <(misses 1)
read -r ll3 d13 < <(misses 3)
awk -v n="$n" -v a="$ll1" -v b="$ll3" -v c="$d11" -v d="$d13" 'BEGIN {
  printf "N = %d: per collision %.2f LL (2 MiB) data misses, %.2f L1 (48 KiB) data misses\n",
         n, (b - a) / (2 * n), (d - c) / (2 * n) }'
