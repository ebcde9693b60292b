// The Hessian size field on analytic lattices: exact Hessians of quadratics,
// the L^p size law, a tanh jump (small at the jump, large away, gradation
// respected), complexity targets met.
#include "pipeline/hessian_size.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scene/errors.hpp"

namespace {

constexpr int kN = 100;         // lattice cells per side on the unit square
constexpr double kJumpX = 0.5;  // the tanh jump's position
constexpr double kJumpWidth = 0.02;
// Central differences are exact on quadratics; only rounding remains.
constexpr double kExactRel = 1e-8;
// The gradation bound holds to rounding.
constexpr double kGradationRel = 1e-9;
// The complexity target is met by bisection on D to 1e-4; the test allows 5e-3.
constexpr double kComplexityRel = 5e-3;

scene::Lattice unit_lattice(double (*f)(double, double)) {
  scene::Lattice lat(kN, kN, 0.0, 0.0, 1.0 / kN, 1.0 / kN);
  auto& v = lat.add("rho");
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) v[lat.index(i, j)] = f(lat.xc(i), lat.yc(j));
  return lat;
}

double jump(double x, double) {
  return 2.0 + std::tanh((x - kJumpX) / kJumpWidth);
}

double lambda_at(const scene::Lattice& lam, int i, int j) {
  return lam.field("lambda")[lam.index(i, j)];
}
double h_at(const scene::Lattice& h, int i, int j) {
  return h.field("h")[h.index(i, j)];
}

}  // namespace

TEST(HessianSize, QuadraticsHaveTheirExactLargestEigenvalue) {
  // 3x^2 + 2xy - y^2: H = [[6, 2], [2, -2]], eigenvalues 2 +- sqrt(20).
  const auto lam = pipeline::hessian_magnitude(
      unit_lattice([](double x, double y) { return 3 * x * x + 2 * x * y - y * y; }), "rho", 1);
  const double exact = 2.0 + std::sqrt(20.0);
  // Cells whose smoothed stencil reaches the lattice edge see a truncated filter.
  for (int j = 2; j < kN - 2; ++j)
    for (int i = 2; i < kN - 2; ++i)
      ASSERT_NEAR(lambda_at(lam, i, j), exact, kExactRel * exact) << i << " " << j;
  // The outer ring copies its inner neighbour.
  EXPECT_EQ(lambda_at(lam, 0, 50), lambda_at(lam, 1, 50));
}

TEST(HessianSize, StencilsMeetingNaNCarryNoInformation) {
  auto lat = unit_lattice([](double x, double y) { return x * x + y * y; });
  lat.fields["rho"][lat.index(50, 50)] = std::numeric_limits<double>::quiet_NaN();
  const auto lam = pipeline::hessian_magnitude(lat, "rho", 0);
  EXPECT_EQ(lambda_at(lam, 51, 50), 0.0);
  EXPECT_EQ(lambda_at(lam, 50, 50), 0.0);
  EXPECT_NEAR(lambda_at(lam, 53, 50), 2.0, kExactRel * 2.0);
  pipeline::SizeTarget t;
  t.h_min = 0.01;
  t.h_max = 0.1;
  t.growth = 1e6;  // no gradation: the raw sizes
  EXPECT_EQ(h_at(pipeline::size_from_hessian(lam, t), 50, 50), t.h_max);
}

TEST(HessianSize, SizesFollowTheLpLaw) {
  // Without clamping or gradation, h ~ lambda^(-p/(2(p+1))): for p = 2, lambda^(-1/3).
  const auto lam = pipeline::hessian_magnitude(unit_lattice(jump), "rho", 1);
  pipeline::SizeTarget t;
  t.h_min = 1e-4;
  t.h_max = 1e6;
  t.growth = 1e6;
  t.norm_p = 2.0;
  const auto h = pipeline::size_from_hessian(lam, t);
  const int i_a = 47, i_b = 44, j = 50;  // near the jump, and further out
  ASSERT_GT(lambda_at(lam, i_b, j), 0.0);
  const double law = std::pow(lambda_at(lam, i_a, j) / lambda_at(lam, i_b, j), -1.0 / 3.0);
  EXPECT_NEAR(h_at(h, i_a, j) / h_at(h, i_b, j), law, kExactRel * law);
  // The largest eigenvalue gets h_min exactly.
  double h_smallest = std::numeric_limits<double>::infinity();
  for (const double v : h.field("h")) h_smallest = std::min(h_smallest, v);
  EXPECT_NEAR(h_smallest, t.h_min, kExactRel * t.h_min);
}

TEST(HessianSize, TanhJumpIsFineAtTheJumpCoarseAwayAndGraded) {
  const auto lam = pipeline::hessian_magnitude(unit_lattice(jump), "rho", 1);
  pipeline::SizeTarget t;
  t.h_min = 0.005;
  t.h_max = 0.05;
  t.growth = 1.2;
  const auto h = pipeline::size_from_hessian(lam, t);
  const double dx = h.dx;
  // Small within the jump's width, largest where tanh'' has decayed (exp(-2 * 0.3 / w) ~ 1e-13).
  constexpr double kFineFactor = 1.5;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const double x = h.xc(i);
      if (std::abs(x - kJumpX) < kJumpWidth) {
        EXPECT_LE(h_at(h, i, j), kFineFactor * t.h_min) << x;
      }
      if (std::abs(x - kJumpX) > 0.3) {
        EXPECT_EQ(h_at(h, i, j), t.h_max) << x;
      }
      EXPECT_GE(h_at(h, i, j), t.h_min);
      EXPECT_LE(h_at(h, i, j), t.h_max);
    }
  // Gradation: neighbours differ by at most (growth - 1) times their distance.
  for (int j = 0; j + 1 < kN; ++j)
    for (int i = 0; i + 1 < kN; ++i) {
      const double bound = (t.growth - 1.0) * dx * (1.0 + kGradationRel);
      ASSERT_LE(std::abs(h_at(h, i + 1, j) - h_at(h, i, j)), bound);
      ASSERT_LE(std::abs(h_at(h, i, j + 1) - h_at(h, i, j)), bound);
      ASSERT_LE(std::abs(h_at(h, i + 1, j + 1) - h_at(h, i, j)), std::sqrt(2.0) * bound);
    }
  // Sizes grow away from the jump.
  EXPECT_LT(h_at(h, 50, 50), h_at(h, 60, 50));
  EXPECT_LT(h_at(h, 60, 50), h_at(h, 70, 50));
}

TEST(HessianSize, ComplexityTargetIsMet) {
  const auto lam = pipeline::hessian_magnitude(unit_lattice(jump), "rho", 1);
  for (const double target : {600.0, 2000.0, 8000.0}) {
    pipeline::SizeTarget t;
    t.h_min = 0.002;
    t.h_max = 0.1;
    t.growth = 1.2;
    t.cells = target;
    const auto h = pipeline::size_from_hessian(lam, t);
    EXPECT_NEAR(pipeline::lattice_complexity(h), target, kComplexityRel * target);
  }
  // More cells than h_min everywhere allows: refused.
  pipeline::SizeTarget t;
  t.h_min = 0.01;
  t.h_max = 0.1;
  t.cells = 1e5;
  EXPECT_THROW(pipeline::size_from_hessian(lam, t), scene::InputError);
}

TEST(HessianSize, BadTargetsAreRefused) {
  const auto lam = pipeline::hessian_magnitude(unit_lattice(jump), "rho", 0);
  pipeline::SizeTarget t;
  t.h_min = 0.1;
  t.h_max = 0.01;
  EXPECT_THROW(pipeline::size_from_hessian(lam, t), scene::InputError);
  t.h_min = 0.01;
  t.h_max = 0.1;
  t.growth = 1.0;
  EXPECT_THROW(pipeline::size_from_hessian(lam, t), scene::InputError);
  t.growth = 1.2;
  t.h_min = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(pipeline::size_from_hessian(lam, t), scene::InputError);
}
