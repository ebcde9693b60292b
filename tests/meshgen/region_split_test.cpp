// The region cut in two for gmsh's threads: closed pieces on either side of
// a vertical cut that together are the region, balanced by estimated cells.
#include "region_split.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "meshgen/fluid_region.hpp"
#include "shock_fixtures.hpp"

namespace {

using scene::Vec2;

constexpr double kExact = 1e-12;  // shared end points (scene units)
constexpr double kAreaTolerance =
    1e-6;                      // pieces' areas against the region's (relative, arc sampling)
constexpr double kSag = 1e-5;  // arc sampling for the areas (scene units)
// Uniform size: the cut halves the area to the balance lattice's resolution
// (1/200 of the width) and the end clearance.
constexpr double kBalanceTolerance = 0.02;
const char* const kCases[] = {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"};

// Signed area of a loop (counter-clockwise positive).
double loop_area(const std::vector<meshgen::PieceCurve>& loop) {
  double a = 0.0;
  for (const meshgen::PieceCurve& pc : loop) {
    const std::vector<Vec2> pts = meshgen::sample_curve(pc.curve, kSag);
    for (std::size_t k = 0; k + 1 < pts.size(); ++k)
      a += 0.5 * (pts[k].x * pts[k + 1].y - pts[k + 1].x * pts[k].y);
  }
  return a;
}

double region_area(const meshgen::FluidRegion& r) {
  double a = 0.0;
  for (const auto& loop : r.loops) {
    std::vector<meshgen::PieceCurve> pcs;
    for (const auto& c : loop) pcs.push_back({c, false});
    a += loop_area(pcs);
  }
  return a;
}

}  // namespace

TEST(RegionSplit, PiecesAreClosedOnEitherSideAndMakeTheRegion) {
  for (const char* name : kCases) {
    const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
    const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
    const auto pieces = meshgen::split_region(r, [](Vec2) { return 1.0; });
    // Wedges always split (the cut crosses the top and the wedge face);
    // blunt bodies may not, then they are meshed whole.
    const bool wedge = std::string(name).rfind("wedge", 0) == 0;
    if (wedge) {
      ASSERT_TRUE(pieces) << name;
    }
    if (!pieces) continue;
    double total = 0.0;
    int cuts = 0;
    for (int side = 0; side < 2; ++side) {
      ASSERT_FALSE(pieces->loops[side].empty()) << name;
      for (const auto& loop : pieces->loops[side]) {
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const auto& c = loop[k].curve;
          EXPECT_NEAR(scene::norm(c.b - loop[(k + 1) % loop.size()].curve.a), 0.0, kExact) << name;
          for (const Vec2 p : meshgen::sample_curve(c, kSag)) {
            if (side == 0)
              EXPECT_LE(p.x, pieces->x + kExact) << name;
            else
              EXPECT_GE(p.x, pieces->x - kExact) << name;
          }
          if (loop[k].cut) {
            ++cuts;
            EXPECT_NEAR(c.a.x, pieces->x, kExact) << name;
            EXPECT_NEAR(c.b.x, pieces->x, kExact) << name;
          }
        }
        total += loop_area(loop);
      }
      EXPECT_GT(loop_area(pieces->loops[side].front()), 0.0)
          << name << ": outer loop not counter-clockwise";
    }
    EXPECT_EQ(cuts, 2) << name;  // once in each piece
    const double area = region_area(r);
    EXPECT_NEAR(total / area, 1.0, kAreaTolerance) << name;
    double left = 0.0;
    for (const auto& loop : pieces->loops[0]) left += loop_area(loop);
    if (wedge) {
      EXPECT_NEAR(left / area, 0.5, kBalanceTolerance) << name;
    }
  }
}
