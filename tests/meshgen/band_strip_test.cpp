// Shock-aligned strips (mesh.anisotropy): the along-shock length rule on a
// straight shock, a circular one and a widening ci. Pure geometry, no gmsh.
#include "band_strip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "meshgen/fluid_region.hpp"
#include "shock_fixtures.hpp"

using scene::Vec2;

namespace {

constexpr double kHMin = 0.01;
// The stations are stretched to end on the run's end: every length shrinks
// by at most one step's worth over the run (under 10% on these runs).
constexpr double kEndStretch = 0.9;
// Curvature and ci slope are measured on chords over a window: 5% slack.
constexpr double kRuleSlack = 1.05;
constexpr double kExact = 1e-9;
constexpr int kPoints = 200;

// wedge_M3_10 in a large free-stream box, so strips fit wherever the tests put them.
meshgen::FluidRegion big_region() {
  scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  s.domain_override = scene::Domain{-1.0, 4.0, 0.0, 4.0, true};
  return meshgen::make_fluid_region(s);
}

meshgen::ShockRun line_run(Vec2 a, Vec2 b, double w0, double w1) {
  meshgen::ShockRun r;
  for (int i = 0; i < kPoints; ++i) {
    const double t = static_cast<double>(i) / (kPoints - 1);
    r.points.push_back(a + t * (b - a));
    r.half_width.push_back(w0 + t * (w1 - w0));
  }
  return r;
}

meshgen::StripRule rule(double aspect) {
  return {kHMin, aspect, 0.2, 1.2};
}

}  // namespace

TEST(BandStrip, StraightShockGetsTheFullAspect) {
  const meshgen::FluidRegion region = big_region();
  const double a = 10.0;
  const meshgen::BandLayout l = meshgen::layout_strips(
      {line_run({0.5, 1.0}, {3.0, 2.5}, 3 * kHMin, 3 * kHMin)}, region, rule(a));
  ASSERT_EQ(l.strips.size(), 1u);
  EXPECT_TRUE(l.uncovered.empty());
  const meshgen::ShockStrip& st = l.strips[0];
  for (const double len : st.along) {
    EXPECT_LE(len, a * kHMin * (1 + kExact));
    EXPECT_GE(len, kEndStretch * a * kHMin);
  }
  // Rows: h_min or thinner across the band (3 h_min each side), growth rows beyond.
  for (std::size_t j = 0; j + 1 < st.rows.size(); ++j) {
    if (std::abs(st.rows[j]) < 3 * kHMin + kExact && std::abs(st.rows[j + 1]) < 3 * kHMin + kExact) {
      EXPECT_LE(st.rows[j + 1] - st.rows[j], kHMin * (1 + kExact));
    }
  }
  EXPECT_GT(st.rows.back(), 3 * kHMin);
  // Columns are square to the shock.
  const Vec2 t = scene::normalized(Vec2{2.5, 1.5});
  for (const Vec2 n : st.normal) EXPECT_NEAR(scene::dot(n, t), 0.0, kExact);
}

TEST(BandStrip, CurvedShockGetsCellsOfATenthOfItsRadius) {
  const meshgen::FluidRegion region = big_region();
  const double radius = 1.0;
  const Vec2 centre{1.5, 1.5};
  meshgen::ShockRun r;
  for (int i = 0; i < kPoints; ++i) {
    const double phi = M_PI * (0.25 + 0.5 * i / (kPoints - 1));
    r.points.push_back(centre + radius * Vec2{std::cos(phi), std::sin(phi)});
    r.half_width.push_back(3 * kHMin);
  }
  const double a = 30.0;  // A h_min = 0.3 > 0.1 R: curvature decides
  const meshgen::BandLayout l = meshgen::layout_strips({r}, region, rule(a));
  ASSERT_EQ(l.strips.size(), 1u);
  const auto& along = l.strips[0].along;
  EXPECT_LE(*std::max_element(along.begin(), along.end()), 0.1 * radius * kRuleSlack);
  EXPECT_GE(*std::min_element(along.begin(), along.end()), kEndStretch * 0.1 * radius / kRuleSlack);
}

TEST(BandStrip, WideningCiShortensTheCells) {
  const meshgen::FluidRegion region = big_region();
  const Vec2 a{0.5, 1.0}, b{3.0, 2.5};
  const double len = scene::norm(b - a);
  const double w0 = 0.05, w1 = 0.25, slope = (w1 - w0) / len;  // w grows by 0.08 per unit length
  const double aspect = 20.0;  // A h_min = 0.2 > h_min / slope = 0.125
  const meshgen::BandLayout l =
      meshgen::layout_strips({line_run(a, b, w0, w1)}, region, rule(aspect));
  ASSERT_EQ(l.strips.size(), 1u);
  for (const double s : l.strips[0].along) EXPECT_LE(s * slope, kHMin * kRuleSlack);
  // The rows follow the local half-width: thinner where ci is smaller.
  EXPECT_LT(l.strips[0].scale.front(), l.strips[0].scale.back());
}
