#!/usr/bin/env bash
# The engine's look-ahead prefetch stages must survive the optimiser.
# GCC once classed them as pure functions (they only read memory and call
# __builtin_prefetch) and deleted their calls, silently: the engine lost a
# third of its large-N speed and every result stayed the same, so no other
# test could see it. This reads the disassembly of prefetch_ahead() in the
# engine library and counts what it does with the memory of coming events:
# prefetch instructions, and calls to the stage functions where the
# compiler did not inline them. The first stage alone is 2; all four are
# 8 (the stages' helpers called) to ~40 (all inlined) with GCC 12 on x86-64.
#
#   look_ahead_in_binary.sh OBJDUMP LIBRARY
set -euo pipefail
objdump=$1
library=$2
# Fewest prefetches or stage calls that stages two to four can leave.
readonly kMinimum=6
# -r: in an unlinked library a call shows its target as a relocation.
body=$("$objdump" -d -r --no-show-raw-insn -C "$library" |
  awk '/^[0-9a-f]+ <.*>:$/ { inside = index($0, "granular::Engine::Impl::prefetch_ahead()>:") > 0; next }
       inside')
if [[ -z $body ]]; then
  echo "FAIL: no granular::Engine::Impl::prefetch_ahead() in $library" >&2
  exit 1
fi
count=$(grep -cE 'prefetch(t0|t1|t2|nta|w)\b|R_[A-Z0-9_]+[[:space:]]+granular::Engine::Impl::prefetch_(stage|block|corner|records)' <<< "$body" || true)
echo "prefetch_ahead(): $count prefetch instructions or stage calls (need >= $kMinimum)"
if (( count < kMinimum )); then
  echo "FAIL: the look-ahead stages were optimised away (see granular/src/engine/prefetch.hpp)" >&2
  exit 1
fi
