#pragma once
// Comparing two families of runs at equal error (docs/verdict.md): a
// log-log fit of error against cost per family, the cost ratio at a target
// error with a 95% interval, and the verdict read from that interval.
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace pipeline {

// One run of a family: its cost (CPU seconds) and its error with the 95%
// half-width of the error measure itself (0 when exact).
struct CostError {
  double cost = 0;
  double error = 0;
  double error_ci = 0;
};

// log(error) = a + b log(cost), least squares. `ok` needs >= 3 runs with
// positive finite cost and error and distinct costs (one degree of freedom
// for the residual scatter).
struct LogLogFit {
  bool ok = false;
  int n = 0;
  double a = 0, b = 0;
  double residual_sd = 0;   // s, on log(error)
  double mean_log_cost = 0;
  double sxx = 0;           // sum of (log cost - mean)^2
  double log_cost_at(double error) const;  // the fit inverted; NaN unless b < 0
};
LogLogFit fit_log_log(const std::vector<CostError>& runs);

struct Interval {
  double value = 0, ci_low = 0, ci_high = 0;  // 95%
};

// Cost of `slow` over cost of `fast` at `target_error`, each read off its
// family's fit. The 95% interval propagates both fits' uncertainty (the
// coefficients drawn from their t distribution with n - 2 degrees of
// freedom) and each run's own error interval (the runs' errors perturbed
// before refitting), by a seeded Monte Carlo of `draws` samples.
struct EqualErrorOptions {
  int draws = 4000;
  std::uint64_t seed = 20261201;
};
Interval cost_ratio_at_error(const std::vector<CostError>& slow, const std::vector<CostError>& fast,
                             double target_error, const EqualErrorOptions& o = {});

// Both families' runs, each with a fixed cost paid once whatever grid it
// runs (a predictor): the fit sees only the costs that grow with the grid,
// and the fixed cost is added to the cost read off it. A constant folded
// into every run's cost instead bends the log-log line it is fitted with
// (the fixed part dominates the coarse runs), which widened the interval.
struct FamilyPair {
  std::vector<CostError> slow, fast;
  double slow_fixed = 0, fast_fixed = 0;
};
Interval cost_ratio_at_error(const FamilyPair& runs, double target_error,
                             const EqualErrorOptions& o = {});

// The same with costs that carry their own uncertainty (a priced cost
// model, one timing's scatter): `sample` returns both families' runs as one
// draw sees them, with freshly drawn costs; the errors are perturbed and the
// fits drawn as above. `nominal` gives the central value.
using CostSampler = std::function<FamilyPair(std::mt19937_64&)>;
Interval cost_ratio_at_error(const FamilyPair& nominal, const CostSampler& sample, double target_error,
                             const EqualErrorOptions& o = {});

// "faster" when the interval lies above 1, "slower" below 1, otherwise
// "not distinguishable" (also when the ratio could not be computed).
std::string verdict_of(const Interval& speedup);

// Cheapest cost at which a family (any order) first reaches `error`: the
// cost of the cheapest run at least that accurate, or, when a crossing
// between two runs adjacent in cost comes earlier, the log-log
// interpolation there. NaN when no run reaches it. Used per run in the
// tables; the verdict uses the fits.
double cheapest_cost_at(std::vector<CostError> runs, double error);

}  // namespace pipeline
