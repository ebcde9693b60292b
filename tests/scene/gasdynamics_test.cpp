// Reference gas dynamics against tabulated values (NACA 1135 and the verification card's figures).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace {
using scene::kDeg;
constexpr double kAngleTolDeg = 0.005;  // tables give 2 decimals
constexpr double kRatioTol = 0.0015;
}  // namespace

TEST(Gasdynamics, ThetaBetaMachCaseStudies) {
  struct Case { double m, theta, beta, p; };
  for (const Case c : {Case{3, 10, 27.38, 2.054}, Case{4, 15, 27.06, 3.697}, Case{5, 20, 29.80, 7.037}}) {
    const auto b = scene::oblique_shock_beta(c.m, c.theta * kDeg, 1.4);
    ASSERT_TRUE(b.has_value());
    EXPECT_NEAR(*b / kDeg, c.beta, kAngleTolDeg + 0.005);
    EXPECT_NEAR(scene::oblique_pressure_ratio(c.m, *b, 1.4), c.p, kRatioTol);
  }
}

TEST(Gasdynamics, DetachedBeyondMaximumDeflection) {
  // M = 3, gamma 1.4: maximum deflection 34.07 deg.
  EXPECT_NEAR(scene::max_deflection(3.0, 1.4) / kDeg, 34.07, 0.01);
  EXPECT_FALSE(scene::oblique_shock_beta(3.0, 35 * kDeg, 1.4).has_value());
  EXPECT_FALSE(scene::oblique_shock_beta(0.8, 5 * kDeg, 1.4).has_value());
}

TEST(Gasdynamics, NormalShockLimit) {
  // beta = 90 deg is the normal shock: M=2 gives p2/p1 = 4.5, rho2/rho1 = 2.667.
  EXPECT_NEAR(scene::oblique_pressure_ratio(2.0, std::numbers::pi / 2, 1.4), 4.5, 1e-12);
  EXPECT_NEAR(scene::oblique_density_ratio(2.0, std::numbers::pi / 2, 1.4), 8.0 / 3.0, 1e-12);
}

TEST(Gasdynamics, BilligCorrelations) {
  EXPECT_NEAR(scene::billig_standoff_cylinder(4.0), 0.386 * std::exp(4.67 / 16.0), 1e-12);
  // The hyperbola passes through its vertex and inverts exactly.
  EXPECT_DOUBLE_EQ(scene::billig_shock_x(4.0, 1.0, 0.0), 0.0);
  const double y = 1.7;
  EXPECT_NEAR(scene::billig_shock_y(4.0, 1.0, scene::billig_shock_x(4.0, 1.0, y)), y, 1e-9);
}

// Rayleigh pitot values from the verification card (NACA 1135, gamma 1.4),
// to the 5 significant digits tabulated; M <= 1 is isentropic (M = 1: 1.8929).
TEST(Gasdynamics, RayleighPitotTable) {
  constexpr double kTableRel = 5e-5;
  const std::pair<double, double> table[] = {{2.0, 5.6404}, {3.0, 12.061}, {3.5, 16.242},
                                             {4.0, 21.068}, {5.0, 32.654}, {8.0, 82.866}};
  for (const auto& [m, ratio] : table)
    EXPECT_NEAR(scene::rayleigh_pitot_ratio(m, 1.4), ratio, kTableRel * ratio) << "M = " << m;
  EXPECT_NEAR(scene::rayleigh_pitot_ratio(1.0, 1.4), 1.8929, 1e-4);
  // Continuous through M = 1 (the normal shock vanishes there).
  EXPECT_NEAR(scene::rayleigh_pitot_ratio(1.0 + 1e-9, 1.4), scene::rayleigh_pitot_ratio(1.0, 1.4), 1e-6);
}

TEST(Gasdynamics, RestStartMinMachIsWhereTheInflowShockStandsStill) {
  // 2/sqrt(3 - gamma): 1.5811 for air. Check it against the shock relation
  // it comes from: a shock of Mach Ms = M induces the velocity M/2.
  constexpr double kRoundOff = 1e-12;
  for (const double g : {1.4, 5.0 / 3.0, 1.1}) {
    const double m = scene::rest_start_min_mach(g);
    EXPECT_NEAR(2.0 / (g + 1.0) * (m - 1.0 / m), 0.5 * m, kRoundOff) << "gamma " << g;
  }
  EXPECT_NEAR(scene::rest_start_min_mach(1.4), std::sqrt(2.5), kRoundOff);
}

TEST(Gasdynamics, DeflectionInvertsTheWeakShockAngle) {
  constexpr double kAngleTol = 1e-9;
  const double beta = *scene::oblique_shock_beta(3.0, 10 * kDeg, 1.4);
  EXPECT_NEAR(scene::oblique_deflection(3.0, beta, 1.4), 10 * kDeg, kAngleTol);
  EXPECT_NEAR(scene::oblique_deflection(3.0, std::numbers::pi / 2, 1.4), 0.0, kAngleTol);
  EXPECT_NEAR(scene::oblique_deflection(3.0, std::asin(1.0 / 3.0), 1.4), 0.0, kAngleTol);
}
