// The drifting cell grid (EngineConfig::grid_speed): cells that move with a
// stream find every contact and every wall, and give the fixed grid's
// trajectories up to round-off. A missed neighbour would never be collided
// with, so the engine's own overlap statistic cannot see it: the overlaps
// are checked by brute force over all pairs and all surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "engine_support.hpp"
#include "scene/errors.hpp"

namespace granular {
namespace {

// Disks of diameter 1 may touch to round-off, never overlap deeper.
constexpr double kRoundOffOverlap = 1e-9;
constexpr double kDiameter = 1.0;
constexpr double kRadius = 0.5;
// Relative drift of kinetic + potential energy in an elastic closed box.
constexpr double kEnergyTolerance = 1e-10;
// Positions of the same disks under a fixed and a drifting grid after about
// two collisions per disk: the grids' different round-off, amplified by the
// collisions' chaos, stays far below this.
constexpr double kSameTrajectory = 1e-9;

double deepest_pair_overlap(const std::vector<test::State>& disks) {
  double worst = 0.0;
  for (std::size_t a = 0; a < disks.size(); ++a)
    for (std::size_t b = a + 1; b < disks.size(); ++b)
      worst = std::max(worst, kDiameter - norm(disks[a].r - disks[b].r));
  return worst;
}

// Deepest penetration of a disk into the outer side of a segment a -> b.
double deepest_wall_overlap(const std::vector<test::State>& disks, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const Vec2 n = perp(normalized(ab));
  double worst = 0.0;
  for (const test::State& d : disks) {
    const double t = dot(d.r - a, ab) / norm2(ab);
    if (t < 0.0 || t > 1.0 || dot(d.r - a, n) < -kRadius) continue;  // beyond the ends or behind
    worst = std::max(worst, kRadius - dot(d.r - a, n));
  }
  return worst;
}

// Disks on a square lattice of the given spacing inside [lo, hi]^2 with
// Gaussian velocities of unit temperature.
void fill_lattice(Engine& e, double lo, double hi, double spacing, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  for (double y = lo + spacing; y < hi - kRadius; y += spacing)
    for (double x = lo + spacing; x < hi - kRadius; x += spacing)
      e.add({x, y}, {normal(rng), normal(rng)});
}

TEST(EngineDrift, FlowPastAWedgeHasNoHiddenOverlap) {
  const double th = 20.0 * std::numbers::pi / 180.0;
  const Vec2 nose{0, 0}, end{60, 60 * std::tan(th)};
  for (const double cell : {1.0, 2.5}) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    FlowConfig c;
    c.xmin = -20;
    c.xmax = 60;
    c.ymin = 0;
    c.ymax = 40;
    c.symmetric = true;
    c.body_chains = {{nose, end}};  // body below, on the right of travel
    c.inflow_speed = 4.0;
    c.packing_fraction = 0.25;  // dense enough for many collisions near the wedge
    c.seed = 3;
    c.cell = cell;
    ASSERT_TRUE(c.comoving_cells);
    FlowSimulation f(c);
    for (int step = 1; step <= 20; ++step) {
      f.run_until(2.0 * step);  // two flow-through times in all
      std::vector<test::State> disks;
      f.for_each_particle([&](Vec2 r, Vec2 v) { disks.push_back({r, v}); });
      EXPECT_LE(deepest_pair_overlap(disks), kRoundOffOverlap) << "t = " << f.time();
      EXPECT_LE(deepest_wall_overlap(disks, nose, end), kRoundOffOverlap) << "t = " << f.time();
      for (const test::State& d : disks) {
        EXPECT_GE(d.r.y, kRadius - kRoundOffOverlap);
        EXPECT_LE(d.r.y, c.ymax - kRadius + kRoundOffOverlap);
      }
    }
    const Stats st = f.stats();
    EXPECT_GT(st.wall_collisions, 0u);
    EXPECT_GT(st.removed, 0u);
    EXPECT_EQ(st.recoveries, 0u);
    EXPECT_LE(st.max_overlap, kRoundOffOverlap);
    EXPECT_DOUBLE_EQ(f.engine().config().grid_speed, c.inflow_speed);
    EXPECT_GT(f.engine().event_counts().wall_rechecks, 0u);
  }
}

// A closed box under a slanted force, its grid drifting across it: walls
// are found through the fixed look-up grid (never tunnelled), every contact
// through the wrapped columns, and energy is conserved.
TEST(EngineDrift, ClosedBoxUnderGravityConservesEnergy) {
  constexpr double size = 30.0;
  EngineConfig c = test::walled_box(size, 1.0);
  c.gravity = {0.3, -1.0};
  c.grid_speed = 2.5;
  c.min_cell = 1.7;
  Engine e(c);
  fill_lattice(e, 0.0, size, 1.6, 5);
  const auto total_energy = [&] {
    double sum = 0.0;
    e.for_each_particle([&](Vec2 r, Vec2 v) { sum += 0.5 * norm2(v) - dot(c.gravity, r); });
    return sum;
  };
  const double e0 = total_energy();
  const auto n = static_cast<std::uint64_t>(test::snapshot(e).size());
  for (int step = 0; step < 8; ++step) {
    e.run_collisions(25 * n);
    EXPECT_LE(deepest_pair_overlap(test::snapshot(e)), kRoundOffOverlap) << "step " << step;
  }
  EXPECT_NEAR(total_energy() / e0, 1.0, kEnergyTolerance);
  EXPECT_EQ(e.stats().recoveries, 0u);
  EXPECT_GT(e.stats().wall_collisions, 0u);
  EXPECT_LE(e.stats().max_overlap, kRoundOffOverlap);
}

// The grid is bookkeeping: a drifting grid of larger cells moves the same
// disks along the same paths as the fixed grid, up to round-off.
TEST(EngineDrift, SameTrajectoriesAsAFixedGrid) {
  constexpr double size = 40.0;
  std::vector<test::State> end[2];
  std::uint64_t collisions[2] = {};
  std::uint64_t crossings[2] = {};
  for (const int k : {0, 1}) {
    EngineConfig c = test::walled_box(size, 1.0);
    if (k == 1) {
      c.grid_speed = 3.0;
      c.min_cell = 2.2;
    }
    Engine e(c);
    fill_lattice(e, 0.0, size, 1.7, 8);
    e.run_collisions(2 * test::snapshot(e).size());
    e.run_until(e.time());  // both stop at the same collision, then compare at one time
    end[k] = test::snapshot(e);
    collisions[k] = e.stats().collisions;
    crossings[k] = e.event_counts().cell_crossings;
  }
  EXPECT_EQ(collisions[0], collisions[1]);
  ASSERT_EQ(end[0].size(), end[1].size());
  double worst = 0.0;
  for (std::size_t i = 0; i < end[0].size(); ++i)
    worst = std::max({worst, norm(end[0][i].r - end[1][i].r), norm(end[0][i].v - end[1][i].v)});
  EXPECT_LE(worst, kSameTrajectory);
  EXPECT_NE(crossings[0], crossings[1]) << "the same cell crossings: the grid did not drift";
}

// The drifting grid's state (columns, per-slot exits and wall horizons) is
// in the checkpoint: a restored engine continues bit-identically.
TEST(EngineDrift, CheckpointContinuesBitIdentically) {
  EngineConfig c = test::walled_box(30.0, 0.9);
  c.gravity = {0.2, -1.0};
  c.grid_speed = 2.0;
  c.min_cell = 1.5;
  c.tc = 1e-4;
  Engine a(c);
  fill_lattice(a, 0.0, 30.0, 1.6, 7);
  const auto n = static_cast<std::uint64_t>(test::snapshot(a).size());
  a.run_collisions(10 * n);
  std::stringstream buf;
  a.save(buf);
  Engine b = Engine::load(buf);
  a.run_collisions(20 * n);
  b.run_collisions(20 * n);
  const auto sa = test::snapshot(a), sb = test::snapshot(b);
  ASSERT_EQ(sa.size(), sb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < sa.size(); ++i)
    differ += sa[i].r.x != sb[i].r.x || sa[i].r.y != sb[i].r.y || sa[i].v.x != sb[i].v.x ||
              sa[i].v.y != sb[i].v.y;
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(a.time(), b.time());
  EXPECT_GT(a.event_counts().wall_rechecks, 0u);
}

TEST(EngineDrift, PeriodicXFacesAreRefused) {
  EngineConfig c = test::open_space(20.0);
  c.grid_speed = 1.0;
  try {
    Engine e(c);
    FAIL() << "a drifting grid with periodic x faces was accepted";
  } catch (const scene::InputError& err) {
    EXPECT_NE(std::string(err.what()).find("non-periodic x faces"), std::string::npos)
        << err.what();
  }
}

}  // namespace
}  // namespace granular
