// The region cut for gmsh's threads: closed pieces between vertical cuts
// that together are the region, balanced by estimated cells.
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
    for (const auto& c : loop) pcs.push_back({c, -1});
    a += loop_area(pcs);
  }
  return a;
}

}  // namespace

TEST(RegionSplit, PiecesAreClosedBetweenTheirCutsAndMakeTheRegion) {
  for (const int n : {2, 4})
    for (const char* name : kCases) {
      const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
      const meshgen::FluidRegion r = meshgen::make_fluid_region(s);
      const auto pieces = meshgen::split_region(r, [](Vec2) { return 1.0; }, n);
      // Wedges always split (the cuts cross the top and the wedge face or
      // the symmetry line); blunt bodies may not, then they are meshed whole.
      const bool wedge = std::string(name).rfind("wedge", 0) == 0;
      if (wedge) {
        ASSERT_TRUE(pieces) << name;
        EXPECT_EQ(pieces->loops.size(), static_cast<std::size_t>(n)) << name;
      }
      if (!pieces) continue;
      ASSERT_EQ(pieces->loops.size(), pieces->x.size() + 1) << name;
      double total = 0.0;
      std::size_t cut_curves = 0;
      const double area = region_area(r);
      for (std::size_t k = 0; k < pieces->loops.size(); ++k) {
        const double lo = k == 0 ? -1e300 : pieces->x[k - 1], hi = k == pieces->x.size() ? 1e300 : pieces->x[k];
        ASSERT_FALSE(pieces->loops[k].empty()) << name;
        double piece_area = 0.0;
        for (const auto& loop : pieces->loops[k]) {
          for (std::size_t c = 0; c < loop.size(); ++c) {
            const auto& curve = loop[c].curve;
            EXPECT_NEAR(scene::norm(curve.b - loop[(c + 1) % loop.size()].curve.a), 0.0, kExact) << name;
            for (const Vec2 p : meshgen::sample_curve(curve, kSag)) {
              EXPECT_GE(p.x, lo - kExact) << name << " piece " << k;
              EXPECT_LE(p.x, hi + kExact) << name << " piece " << k;
            }
            if (loop[c].cut >= 0) {
              ++cut_curves;
              const double x = pieces->x[static_cast<std::size_t>(loop[c].cut)];
              EXPECT_NEAR(curve.a.x, x, kExact) << name;
              EXPECT_NEAR(curve.b.x, x, kExact) << name;
            }
          }
          piece_area += loop_area(loop);
        }
        EXPECT_GT(loop_area(pieces->loops[k].front()), 0.0) << name << ": outer loop not counter-clockwise";
        if (wedge) {
          EXPECT_NEAR(piece_area / area, 1.0 / n, kBalanceTolerance) << name << " piece " << k;
        }
        total += piece_area;
      }
      EXPECT_EQ(cut_curves, 2 * pieces->x.size()) << name;  // each cut in the pieces either side
      EXPECT_NEAR(total / area, 1.0, kAreaTolerance) << name;
    }
}
