// The two-line fit on 1D profiles: exhaustive O(n) breakpoint search against
// brute force, and the shock position for a kink and for a step.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "shockfit/two_line_fit.hpp"

using shockfit::best_breakpoint;
using shockfit::fit_two_lines;
using shockfit::TwoLineOptions;

namespace {

constexpr double kRoundOff = 1e-9;

double brute_sse(const std::vector<double>& t, const std::vector<double>& f, int i, int j) {
  Eigen::MatrixXd X(j - i, 2);
  Eigen::VectorXd y(j - i);
  for (int k = i; k < j; ++k) {
    X(k - i, 0) = 1;
    X(k - i, 1) = t[k];
    y(k - i) = f[k];
  }
  const Eigen::VectorXd c = X.colPivHouseholderQr().solve(y);
  return (X * c - y).squaredNorm();
}

std::vector<double> grid(int n, double h) {
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k) t[k] = k * h;
  return t;
}

}  // namespace

TEST(TwoLineFit, BreakpointMatchesBruteForce) {
  const std::uint64_t seed = 7;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  const std::vector<double> t = grid(120, 0.01);
  std::vector<double> f(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) f[k] = 1000.0 + (t[k] < 0.7 ? 2.0 * t[k] : 0.5) + noise(rng);
  const int m = 5;
  int best = -1;
  double best_sse = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(t.size());
  for (int k = m; k <= n - m; ++k) {
    const double sse = brute_sse(t, f, 0, k) + brute_sse(t, f, k, n);
    if (sse < best_sse) { best_sse = sse; best = k; }
  }
  EXPECT_EQ(best_breakpoint(t, f, m), best) << "seed " << seed;
}

TEST(TwoLineFit, TooShortIsInvalid) {
  const std::vector<double> t = grid(10, 1.0), f(10, 1.0);
  TwoLineOptions opt;
  opt.min_segment = 8;
  EXPECT_FALSE(fit_two_lines(t, f, opt).valid);
  EXPECT_EQ(best_breakpoint(t, f, 8), -1);
}

TEST(TwoLineFit, KinkIsTheIntersection) {
  // A ramp into a plateau at t = 0.4123: the lines are exact, so the
  // intersection is the kink to round-off.
  const double tk = 0.4123;
  const std::vector<double> t = grid(200, 0.005);
  std::vector<double> f(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) f[k] = t[k] < tk ? 3.0 - 5.0 * (t[k] - tk) : 3.0;
  TwoLineOptions opt;
  opt.window = 0.02;
  const auto r = fit_two_lines(t, f, opt);
  ASSERT_TRUE(r.valid);
  EXPECT_TRUE(r.kink);
  EXPECT_TRUE(r.accepted);
  EXPECT_NEAR(r.position, tk, 1e-6);
}

TEST(TwoLineFit, TanhStepCentre) {
  // A symmetric tanh step between two levels: the lines are nearly parallel,
  // the position is the centre of the step (equal areas), to a small
  // fraction of the sample spacing.
  const double h = 0.005, tc = 0.3217, width = 0.004;
  const std::vector<double> t = grid(160, h);
  std::vector<double> f(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) f[k] = 2.0 - 0.5 * (1 + std::tanh((t[k] - tc) / width));
  TwoLineOptions opt;
  opt.window = 8 * h;
  const auto r = fit_two_lines(t, f, opt);
  ASSERT_TRUE(r.valid);
  EXPECT_FALSE(r.kink);
  EXPECT_TRUE(r.accepted);
  constexpr double kStepTolerance = 0.05;  // of the sample spacing
  EXPECT_NEAR(r.position, tc, kStepTolerance * h);
  EXPECT_NEAR(r.step, -1.0, 0.05);
}

TEST(TwoLineFit, NoiseAloneIsRejected) {
  TwoLineOptions opt;
  opt.window = 0.04;
  opt.correlation = 1.0;
  int accepted = 0;
  constexpr int kTrials = 50;
  for (int s = 0; s < kTrials; ++s) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(s));
    std::normal_distribution<double> noise(0.0, 0.1);
    const std::vector<double> t = grid(150, 0.01);
    std::vector<double> f(t.size());
    for (auto& v : f) v = 1.0 + noise(rng);
    accepted += fit_two_lines(t, f, opt).accepted ? 1 : 0;
  }
  EXPECT_EQ(accepted, 0) << "seeds 0.." << kTrials - 1;
}

TEST(TwoLineFit, SmoothCurveIsRejected) {
  // A smooth, steep decay (the stagnation line of subsonic flow) has no
  // jump, with or without noise.
  for (const double sigma : {0.0, 0.01}) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    const std::vector<double> t = grid(200, 0.005);
    std::vector<double> f(t.size());
    for (std::size_t k = 0; k < t.size(); ++k) f[k] = 1.0 + 0.4 / std::pow(1.0 + t[k] / 0.2, 2) + sigma * noise(rng);
    TwoLineOptions opt;
    opt.window = 0.02;
    opt.correlation = 2.0;
    EXPECT_FALSE(fit_two_lines(t, f, opt).accepted) << "sigma " << sigma;
  }
}
