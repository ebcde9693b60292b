// The predicted shock carried to the flow region's edge: pure geometry.
#include "meshgen/shock_extension.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/body_traits.hpp"
#include "shock_fixtures.hpp"

using scene::Vec2;

namespace {

constexpr double kOnLine = 1e-9;    // an exact straight shock stays on its line
constexpr double kOnEdge = 1e-6;    // an exit point lies on the region's edge (bisection)
constexpr double kNearApex = 2e-3;  // the exact attached shock starts at the apex

// The exact shock of a wedge case, kept only between x0 and x1 as the
// predictor's accepted stations would be.
std::vector<Vec2> truncated_wedge_shock(const scene::Scene& s, double x0, double x1, int n) {
  const double beta = *scene::attached_shock_beta(s);
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (x1 - x0) * i / (n - 1);
    pts.push_back({x, x * std::tan(beta)});
  }
  return pts;
}

bool on_domain_edge(const scene::Domain& d, Vec2 p) {
  return std::abs(p.x - d.xmax) < kOnEdge || std::abs(p.y - d.ymax) < kOnEdge ||
         std::abs(p.x - d.xmin) < kOnEdge || std::abs(p.y - d.ymin) < kOnEdge;
}

}  // namespace

TEST(ShockExtension, AnAttachedShockRunsFromTheApexToTheDomainEdgeOnItsLine) {
  for (const char* name : {"wedge_M3_10", "wedge_M5_20"}) {
    SCOPED_TRACE(name);
    const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
    const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
    const double beta = *scene::attached_shock_beta(s);
    const std::vector<Vec2> cut = truncated_wedge_shock(s, 0.1, 0.8, 30);
    const meshgen::ExtendedShock e = meshgen::extend_shock_to_boundary(cut, {}, r);
    ASSERT_EQ(e.curve.size(), cut.size() + 2);
    EXPECT_TRUE(e.ci.empty());
    for (const Vec2 p : e.curve) EXPECT_NEAR(p.y, p.x * std::tan(beta), kOnLine);
    EXPECT_LT(scene::norm(e.curve.front()), kNearApex);
    EXPECT_TRUE(on_domain_edge(r.domain, e.curve.back()));
    EXPECT_NEAR(e.start_length, 0.1 / std::cos(beta), kNearApex);
    EXPECT_GT(e.end_length, 0.0);
  }
}

TEST(ShockExtension, TheBandWidensWithTheDistanceExtrapolated) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M4_15"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const std::vector<Vec2> cut = truncated_wedge_shock(s, 0.2, 0.6, 19);
  constexpr double kCi = 0.004;
  const std::vector<double> ci(cut.size(), kCi);
  const meshgen::ExtendedShock e = meshgen::extend_shock_to_boundary(cut, ci, r);
  ASSERT_EQ(e.ci.size(), e.curve.size());
  // The end stretch is the fewest intervals that reach a quarter of the
  // curve's length (5 of 18): w(s) = ci + s 2 ci / L_stretch on a straight
  // curve (no curvature term), and s never beyond L_stretch: the outlet is
  // farther than that from x = 0.6, the apex end reaches y = 0 first.
  const double stretch = scene::norm(cut[18] - cut[13]);
  EXPECT_NEAR(e.end_length, stretch, 1e-12);
  EXPECT_NEAR(e.ci.back(), kCi + e.end_length * 2.0 * kCi / stretch, 1e-9);
  EXPECT_NEAR(e.ci.front(), kCi + e.start_length * 2.0 * kCi / stretch, 1e-9);
  EXPECT_NEAR(e.start_length, stretch, 1e-12);
}

TEST(ShockExtension, ACurvedEndWidensWithItsCurvature) {
  // An arc of radius R: carried straight along its end stretch's mean
  // direction, it leaves the circle by about s (s + L) / (2 R), which the
  // half-width must cover.
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  constexpr double kRadius = 0.8, kPi = 3.14159265358979323846;
  const Vec2 centre{0.4, -0.3};
  std::vector<Vec2> arc;
  for (int i = 0; i <= 40; ++i) {
    const double a = (100.0 - i) * kPi / 180.0;
    arc.push_back(centre + kRadius * Vec2{std::cos(a), std::sin(a)});
  }
  const meshgen::ExtendedShock e = meshgen::extend_shock_to_boundary(arc, {}, r);
  ASSERT_EQ(e.ci.size(), 0u);
  const meshgen::ExtendedShock w =
      meshgen::extend_shock_to_boundary(arc, std::vector<double>(arc.size(), 0.0), r);
  ASSERT_EQ(w.ci.size(), w.curve.size());
  const double s_end = w.end_length;
  ASSERT_GT(s_end, 0.1);
  // How far the straight extension's end lies from the circle.
  const double off = std::abs(scene::norm(w.curve.back() - centre) - kRadius);
  const double stretch = kRadius * 10.0 * kPi / 180.0;  // a quarter of the 40-degree arc
  EXPECT_NEAR(w.ci.back(), s_end * (s_end + stretch) / (2.0 * kRadius), 0.1 * w.ci.back());
  EXPECT_GE(w.ci.back(), 0.9 * off);
}

TEST(ShockExtension, ABowShockLeavesTheRegionAtBothEnds) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("disc_M4"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  // Billig's shock kept over its middle: both ends extrapolated.
  std::vector<Vec2> shock = meshgen_test::predicted_shock(s, 60);
  std::vector<Vec2> middle(shock.begin() + 5, shock.begin() + 30);
  const meshgen::ExtendedShock e = meshgen::extend_shock_to_boundary(middle, {}, r);
  ASSERT_EQ(e.curve.size(), middle.size() + 2);
  EXPECT_TRUE(on_domain_edge(r.domain, e.curve.front()));
  EXPECT_TRUE(on_domain_edge(r.domain, e.curve.back()));
  for (const Vec2 p : e.curve)
    EXPECT_TRUE(p.x >= r.domain.xmin - kOnEdge && p.x <= r.domain.xmax + kOnEdge);
}

TEST(ShockExtension, PointsAndEndsOutsideTheRegionAreLeftAlone) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const std::vector<Vec2> one{{0.5, 0.4}};
  EXPECT_EQ(meshgen::extend_shock_to_boundary(one, {}, r).curve.size(), 1u);
  // A curve that already runs past the outlet gains nothing at that end.
  const std::vector<Vec2> past = meshgen_test::predicted_shock(s, 40);
  const meshgen::ExtendedShock e = meshgen::extend_shock_to_boundary(past, {}, r);
  EXPECT_EQ(e.end_length, 0.0);
  EXPECT_EQ(e.curve.back(), past.back());
}
