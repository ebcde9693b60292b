// The cell grid finds every contact: boxes whose cell counts leave every
// remainder modulo the 4 x 4 head tiles (partly filled tiles at the right
// and top edges), periodic and walled, checked against a brute-force
// all-pairs overlap test. A neighbour the grid failed to look at would not
// be collided with, so the engine's own overlap statistic would never see
// it: only an independent check can.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "engine_support.hpp"
#include "granular/box_setup.hpp"

namespace granular {
namespace {

// Disks of diameter 1 may touch to round-off, never overlap deeper.
constexpr double kRoundOffOverlap = 1e-9;
constexpr double kEnergyTolerance = 1e-10;
constexpr double kDiameter = 1.0;

// Deepest overlap of any pair (minimum image on periodic sides).
double deepest_overlap(const Engine& e, double lx, double ly, bool periodic) {
  const auto disks = test::snapshot(e);
  double worst = 0.0;
  for (std::size_t a = 0; a < disks.size(); ++a)
    for (std::size_t b = a + 1; b < disks.size(); ++b) {
      double dx = disks[a].r.x - disks[b].r.x, dy = disks[a].r.y - disks[b].r.y;
      if (periodic) {
        dx -= lx * std::round(dx / lx);
        dy -= ly * std::round(dy / ly);
      }
      worst = std::max(worst, kDiameter - std::sqrt(dx * dx + dy * dy));
    }
  return worst;
}

void check_box(double width, double height, bool periodic) {
  SCOPED_TRACE("box " + std::to_string(width) + " x " + std::to_string(height) +
               (periodic ? " periodic" : " walled"));
  BoxSetup b;
  b.width = width;
  b.height = height;
  b.periodic = periodic;
  b.packing_fraction = 0.5;
  b.particles = static_cast<std::int64_t>(0.5 * width * height / (std::numbers::pi / 4.0));
  b.seed = 11;
  Engine e = make_box_engine(b);
  const double e0 = test::kinetic_energy(e);
  for (int step = 0; step < 8; ++step) {
    e.run_collisions(static_cast<std::uint64_t>(25 * b.particles));
    EXPECT_LE(deepest_overlap(e, width, height, periodic), kRoundOffOverlap) << "step " << step;
  }
  EXPECT_NEAR(test::kinetic_energy(e) / e0, 1.0, kEnergyTolerance);
  EXPECT_EQ(e.stats().recoveries, 0u);
}

TEST(EngineGrid, EveryContactIsFoundWhateverTheTileRemainder) {
  // 5..11 cells a side: remainders 1, 2, 3 and 0 modulo 4 in both directions.
  for (const bool periodic : {true, false}) {
    check_box(5.3, 10.6, periodic);
    check_box(6.2, 7.4, periodic);
    check_box(11.5, 9.1, periodic);
    check_box(8.0, 12.0, periodic);
  }
}

// The look-ahead prefetching is a hint: with the full look-ahead forced on
// (it is automatic only from ~32 MB up), trajectories are the same bit for
// bit as with the records-only one, in a periodic box and in a walled one
// (whose edge cells take the look-ahead's clamped and wrapped paths).
TEST(EngineGrid, LookAheadChangesNoResult) {
  for (const bool periodic : {true, false}) {
    SCOPED_TRACE(periodic ? "periodic" : "walled");
    std::vector<test::State> end[2];
    std::uint64_t collisions[2] = {};
    for (const LookAhead mode : {LookAhead::records, LookAhead::full}) {
      BoxSetup b;
      b.width = 110.0;  // 5,900 disks: the slots are renumbered every 10 collisions per disk
      b.height = 105.0;
      b.periodic = periodic;
      b.packing_fraction = 0.4;
      b.particles = static_cast<std::int64_t>(0.4 * b.width * b.height / (std::numbers::pi / 4.0));
      b.seed = 5;
      b.look_ahead = mode;
      Engine e = make_box_engine(b);
      e.run_collisions(static_cast<std::uint64_t>(25 * b.particles));
      const int k = mode == LookAhead::full ? 1 : 0;
      end[k] = test::snapshot(e);
      collisions[k] = e.stats().collisions;
    }
    EXPECT_EQ(collisions[0], collisions[1]);
    ASSERT_EQ(end[0].size(), end[1].size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < end[0].size(); ++i)
      differ += end[0][i].r.x != end[1][i].r.x || end[0][i].r.y != end[1][i].r.y ||
                end[0][i].v.x != end[1][i].v.x || end[0][i].v.y != end[1][i].v.y;
    EXPECT_EQ(differ, 0u);
  }
}

}  // namespace
}  // namespace granular
