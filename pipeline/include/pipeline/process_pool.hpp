#pragma once
// Independent runs in child processes (sweeps, parametric studies): a crash
// or a leak in one run cannot take the others down, and each child's CPU
// time reaches the parent through wait().
#include <functional>

namespace pipeline {

// Runs `work(k)` for k in [0, n) in up to `jobs` child processes at a time
// (in this process when jobs <= 1). Stops starting new ones on Ctrl-C; a
// child that fails is logged, not fatal.
void for_each_in_processes(int n, int jobs, const std::function<int(int)>& work);

}  // namespace pipeline
