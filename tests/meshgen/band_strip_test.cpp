// Shock-aligned strips (mesh.anisotropy): the along-shock length rule on a
// straight shock and a circular one, and a widening ci split into strips.
// Pure geometry, no gmsh.
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
// A strip of n >= 3 cells shrinks them by at most n / (n + 1).
constexpr double kShortRunStretch = 0.75;
// Curvature is measured on chords over a window: 5% slack.
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

TEST(BandStrip, WideningCiSplitsTheShockIntoStripsWhoseRowsStayAtHMin) {
  const meshgen::FluidRegion region = big_region();
  const Vec2 a{0.5, 1.0}, b{3.0, 2.5};
  const double w0 = 0.05, w1 = 0.25;  // ci grows fivefold along the shock
  const double aspect = 20.0;
  const meshgen::BandLayout l =
      meshgen::layout_strips({line_run(a, b, w0, w1)}, region, rule(aspect));
  // Strips whose ci varies by at most 2x: 0.05-0.1, 0.1-0.2, 0.2-0.25.
  ASSERT_EQ(l.strips.size(), 3u);
  const auto w_at = [&](Vec2 p) {
    return w0 + (w1 - w0) * scene::dot(p - a, b - a) / scene::norm2(b - a);
  };
  for (const meshgen::ShockStrip& st : l.strips) {
    double w_lo = 1e300, w_hi = 0;
    for (const Vec2 c : st.centre) {
      w_lo = std::min(w_lo, w_at(c));
      w_hi = std::max(w_hi, w_at(c));
    }
    // The band: equal rows out from the shock (the centre row index is m / 2).
    const std::size_t mid = st.rows.size() / 2;
    ASSERT_NEAR(st.rows[mid], 0.0, kExact);
    const double row = st.rows[mid + 1] - st.rows[mid];
    std::size_t k = mid + 1;
    while (k + 1 < st.rows.size() && std::abs(st.rows[k + 1] - st.rows[k] - row) < kExact) ++k;
    const double band = st.rows[k];
    // Every column spans the widest ci along its strip, in rows of at most
    // h_min and, that width being at least 5 h_min, at least 4/5 of it: a
    // narrow ci elsewhere never thins them (the thinnest row sets the step).
    EXPECT_GE(band, w_hi * (1 - kExact));
    EXPECT_LE(band, 2.0 * w_lo + kHMin);
    EXPECT_LE(row, kHMin * (1 + kExact));
    EXPECT_GE(row, 0.8 * kHMin);
    // The ci's change does not shorten the cells: a straight shock keeps the
    // full aspect, less the end stretch of a strip only a few cells long.
    for (const double len : st.along) EXPECT_GE(len, kShortRunStretch * aspect * kHMin);
  }
  // The gaps between strips keep the isotropic band.
  EXPECT_EQ(l.uncovered.size(), 2u);
}
