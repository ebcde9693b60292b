// Flow region, shock clipping and size field: pure geometry, no gmsh.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "meshgen/fluid_region.hpp"
#include "meshgen/size_field.hpp"
#include "shock_fixtures.hpp"

using meshgen::Patch;
using scene::Vec2;

namespace {

constexpr double kExact = 1e-12;         // coordinates that must be exact
constexpr double kAreaTolerance = 0.01;  // region area vs lattice count (relative)
const char* const kCases[] = {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"};

double lattice_area(const meshgen::FluidRegion& r, int n) {
  const scene::Domain& d = r.domain;
  long inside = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      inside += r.contains({d.xmin + (i + 0.5) * d.width() / n, d.ymin + (j + 0.5) * d.height() / n});
  return d.width() * d.height() * static_cast<double>(inside) / (static_cast<double>(n) * n);
}

}  // namespace

TEST(FluidRegion, EveryCaseIsOneClosedLoopWithAllPatches) {
  for (const char* name : kCases) {
    SCOPED_TRACE(name);
    const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
    const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
    ASSERT_EQ(r.loops.size(), 1u);  // symmetric domains: the body is part of the outer loop
    const auto& loop = r.loops[0];
    std::set<Patch> patches;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      EXPECT_LT(scene::norm(loop[i].b - loop[(i + 1) % loop.size()].a), kExact) << "gap after curve " << i;
      patches.insert(loop[i].patch);
    }
    EXPECT_EQ(patches, (std::set<Patch>{Patch::inlet, Patch::outlet, Patch::top, Patch::bottom, Patch::body}));
    EXPECT_NEAR(r.area(), lattice_area(r, 800), kAreaTolerance * r.area());
  }
}

TEST(FluidRegion, WedgeFaceIsExactAndRunsOutThroughTheOutlet) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M4_15"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const double th = 15.0 * std::acos(-1.0) / 180.0;
  const auto& body = r.loops[0][0];
  EXPECT_EQ(body.patch, Patch::body);
  EXPECT_FALSE(body.is_arc);
  EXPECT_LT(scene::norm(body.a - Vec2{0, 0}), kExact);
  EXPECT_LT(scene::norm(body.b - Vec2{std::cos(th), std::sin(th)}), kExact);
  EXPECT_FALSE(r.outlet_moved);
  EXPECT_DOUBLE_EQ(r.domain.xmax, r.scene_domain.xmax);
}

TEST(FluidRegion, DiscKeepsExactArcsAndMovesTheOutletOutOfTheRearCusp) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("disc_M4"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  // The disc's rear point is tangent to x = xmax: the outlet moves to the
  // thickest station, x = 0, where it meets the body square on.
  EXPECT_TRUE(r.outlet_moved);
  EXPECT_NEAR(r.domain.xmax, 0.0, kExact);
  const double radius = s.body->radius;
  for (const auto& c : r.loops[0]) {
    if (c.patch != Patch::body) continue;
    EXPECT_TRUE(c.is_arc);
    EXPECT_NEAR(scene::norm(c.a - c.center), radius, kExact);
    EXPECT_NEAR(scene::norm(c.b - c.center), radius, kExact);
  }
}

TEST(FluidRegion, ApolloHeatShieldAndShoulderAreArcs) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("apollo_M5"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  int arcs = 0;
  for (const auto& c : r.loops[0]) arcs += c.patch == Patch::body && c.is_arc;
  EXPECT_GE(arcs, 2);  // heat shield + shoulder
  EXPECT_NEAR(r.loops[0][0].center.x, 1.2 * s.body->diameter, kExact);  // shield radius 1.2 D
}

TEST(ClipShock, CurveLeavingTheDomainIsCutAtTheBoundary) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const auto curve = meshgen_test::predicted_shock(s);  // runs 20% past the outlet
  const double resolution = 1e-3;
  const auto runs = meshgen::clip_shock(curve, std::vector<double>(curve.size(), 0.02), r, resolution);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NEAR(runs[0].points.back().x, r.domain.xmax, resolution);
  for (const Vec2 p : runs[0].points) EXPECT_LE(p.x, r.domain.xmax);
}

TEST(ClipShock, CurveCrossingTheBodyStopsAtItsSurface) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  // y = 0.05 from upstream runs into the wedge face at x = 0.05 / tan 10 deg.
  const double y = 0.05, x_hit = y / std::tan(10.0 * std::acos(-1.0) / 180.0);
  const double resolution = 1e-3;
  const auto runs = meshgen::clip_shock({{-0.1, y}, {0.9, y}}, {}, r, resolution);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NEAR(runs[0].points.back().x, x_hit, resolution);
  // Wholly inside the body: nothing left.
  EXPECT_TRUE(meshgen::clip_shock({{0.5, 0.01}, {0.9, 0.02}}, {}, r, resolution).empty());
}

TEST(SizeField, FineInTheBandCoarseFarAwayAndGrowthBounded) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("disc_M4"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const auto curve = meshgen_test::predicted_shock(s);
  const double w = 0.03;
  const auto runs = meshgen::clip_shock(curve, std::vector<double>(curve.size(), w), r, 1e-3);
  const meshgen::SizeParams p{0.01, 0.08, 0.03, 1.15};
  const meshgen::SizeField f(p, runs, r.body.polyline);
  // On the curve and at the band's edge: h_min.
  const Vec2 on = runs[0].points[3];
  EXPECT_DOUBLE_EQ(f(on), p.h_min);
  EXPECT_TRUE(f.in_band(on + Vec2{-0.9 * w, 0}));
  EXPECT_DOUBLE_EQ(f(on + Vec2{-0.9 * w, 0}), p.h_min);
  // Far upstream corner: h_max.
  EXPECT_DOUBLE_EQ(f({r.domain.xmin + 1e-3, r.domain.ymax - 1e-3}), p.h_max);
  // Growth: |h(a) - h(b)| <= (growth - 1) |a - b| (neighbour ratio bounded).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(r.domain.xmin, r.domain.xmax), uy(r.domain.ymin, r.domain.ymax);
  std::uniform_real_distribution<double> ud(-0.02, 0.02);
  constexpr double kSlack = 1e-9;
  for (int k = 0; k < 20000; ++k) {
    const Vec2 a{ux(rng), uy(rng)}, b = a + Vec2{ud(rng), ud(rng)};
    const double ha = f(a), hb = f(b);
    ASSERT_LE(std::abs(ha - hb), (p.growth - 1.0) * scene::norm(a - b) + kSlack) << a.x << "," << a.y;
    ASSERT_GE(ha, p.h_min);
    ASSERT_LE(ha, p.h_max);
  }
}

TEST(SizeField, UniformEstimateIsAreaOverHSquared) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("apollo_M5"));
  const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
  const double h = 0.05;
  EXPECT_NEAR(meshgen::estimate_cells(meshgen::SizeField(h), r), r.area() / (h * h), 0.01 * r.area() / (h * h));
}
