#pragma once
// A cache prefetch hint that the optimiser keeps.
//
// __builtin_prefetch has no side effect as far as GCC is concerned, so a
// function that only reads memory and prefetches counts as pure, and a call
// to it whose (void) result is unused is deleted: GCC 12 -O2 removed three of
// the engine's four look-ahead stages that way, silently, and the large-N
// rate paid for the misses they were meant to hide. The empty asm volatile
// is a side effect the optimiser must keep, which keeps the call and the
// prefetch with it; it emits no instruction.
namespace granular::detail {

inline void prefetch(const void* address) {
  __builtin_prefetch(address);
  asm volatile("" : : "r"(address));
}

}  // namespace granular::detail
