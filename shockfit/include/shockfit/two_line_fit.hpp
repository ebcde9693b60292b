#pragma once
// Two-line fit of a 1D profile f(t): the breakpoint that minimises the total
// squared error of two independent least-squares lines, found exhaustively
// in O(n) with running sums, then the shock position on the profile.
#include <vector>

namespace shockfit {

struct Line {
  double a = 0.0, b = 0.0;  // f = a + b t
  double var_a = 0.0, var_b = 0.0, cov_ab = 0.0;
  double at(double t) const { return a + b * t; }
  double var_at(double t) const { return var_a + 2.0 * t * cov_ab + t * t * var_b; }
};

struct TwoLineOptions {
  double window = 0.04;      // half-width of the shock window (profile units)
  double correlation = 1.0;  // samples per independent noise sample (>= 1)
  double noise_factor = 3.0;
  int min_segment = 8;       // fewest samples in each line
};

struct TwoLineFit {
  bool valid = false;        // enough samples to fit at all
  bool accepted = false;     // a jump stands out of the noise
  int breakpoint = 0;        // first sample of the outer line
  double t_break = 0.0;      // midway between the two segments
  Line inner, outer;         // near the body, away from it
  double position = 0.0;     // shock position on the profile
  double sigma_position = 0.0;
  bool kink = false;         // the lines cross in the window (position = their intersection)
  double step = 0.0;         // outer - inner at t_break
  double noise = 0.0;        // robust per-sample noise of the residuals
  double rms = 0.0;          // root-mean-square residual of the two lines (fit error)
  const char* rejected_by = "too few samples";  // why not accepted ("" when accepted)
};

// t strictly increasing; f finite. Never throws; `valid` false when the
// profile is shorter than two segments.
TwoLineFit fit_two_lines(const std::vector<double>& t, const std::vector<double>& f,
                         const TwoLineOptions& opt);

// Exhaustive breakpoint search alone (exposed for tests): returns k in
// [m, n - m] minimising SSE(0..k-1) + SSE(k..n-1), or -1 when n < 2m.
int best_breakpoint(const std::vector<double>& t, const std::vector<double>& f, int min_segment);

}  // namespace shockfit
