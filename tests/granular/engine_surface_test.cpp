// Walls, vertices and gravity: exact bounce heights, vertex reflection,
// one-sidedness, and no overlap when disks slide into a wedge tip.
#include <gtest/gtest.h>

#include <cmath>

#include "engine_support.hpp"

namespace granular {
namespace {

constexpr double kExact = 1e-12;
// A closed-form bounce sequence accumulates round-off over its bounces.
constexpr double kBounceTolerance = 1e-10;
// Largest overlap allowed anywhere: round-off only.
constexpr double kRoundOffOverlap = 1e-10;

TEST(EngineSurface, BounceUnderGravityMatchesClosedForm) {
  const double ew = 0.8, g = 2.0, h0 = 4.0;  // h0: drop height of the centre above contact
  EngineConfig c = test::walled_box(20.0, ew);
  c.gravity = {0, -g};
  Engine e(c);
  e.add({10, 0.5 + h0}, {0, 0});
  double t = std::sqrt(2.0 * h0 / g);
  double v = g * t;  // impact speed
  for (int k = 0; k < 8; ++k) {
    e.run_collisions(1);
    ASSERT_NEAR(e.time(), t, kBounceTolerance * (1 + t)) << "bounce " << k;
    v *= ew;
    const double apex_t = t + v / g;
    e.run_until(apex_t);
    const double h = v * v / (2.0 * g);  // = ew^(2(k+1)) h0
    EXPECT_NEAR(h, std::pow(ew, 2 * (k + 1)) * h0, kBounceTolerance);
    EXPECT_NEAR(test::snapshot(e)[0].r.y, 0.5 + h, kBounceTolerance) << "apex " << k;
    t += 2.0 * v / g;
  }
}

TEST(EngineSurface, RestitutionZeroUnderGravityNeverStalls) {
  // e = 0 leaves the disk resting on the floor with zero normal velocity;
  // time must keep advancing and the disk must stay on the floor.
  EngineConfig c = test::walled_box(20.0, 0.0);
  c.gravity = {0.2, -1.0};
  c.tc = 1e-3;
  Engine e(c);
  e.add({5, 3}, {0, 0});
  e.run_until(4.0);
  EXPECT_EQ(e.time(), 4.0);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[0].r.y, 0.5, 1e-4);  // TC bounces at most ~ g tc^2
  EXPECT_LE(e.stats().max_overlap, kRoundOffOverlap);
}

TEST(EngineSurface, DiskAimedAtVertexReflectsAboutVertexNormal) {
  EngineConfig c = test::open_space();
  c.vertices = {{{10, 10}, -1.0}};
  Engine e(c);
  e.add({5, 10.3}, {1, 0});
  e.run_collisions(1);
  // Contact at |(x - 10, 0.3)| = 0.5: x = 9.6, t = 4.6; normal (-0.8, 0.6).
  EXPECT_NEAR(e.time(), 4.6, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[0].v.x, -0.28, kExact);
  EXPECT_NEAR(s[0].v.y, 0.96, kExact);
}

TEST(EngineSurface, DiskFallingOnVertexUnderGravity) {
  EngineConfig c = test::open_space();
  c.vertices = {{{10, 10}, -1.0}};
  c.gravity = {0, -1};
  c.left = c.right = c.bottom = c.top = Face::open;
  Engine e(c);
  e.add({10.3, 15}, {0, 0});
  e.run_collisions(1);
  // Contact at height 10.4: fall 4.6, t = sqrt(9.2); normal (0.6, 0.8).
  const double t = std::sqrt(9.2);
  EXPECT_NEAR(e.time(), t, kExact);
  const auto s = test::snapshot(e);
  const double vn = -t * 0.8;
  EXPECT_NEAR(s[0].v.x, -2 * vn * 0.6, kExact);
  EXPECT_NEAR(s[0].v.y, -t - 2 * vn * 0.8, kExact);
}

TEST(EngineSurface, WallsAreOneSided) {
  EngineConfig c = test::open_space();
  c.walls = {{{20, 30}, {20, 10}, -1.0}};  // outward normal +x
  Engine e(c);
  e.add({15, 20}, {1, 0});   // behind the wall: passes through
  e.add({25, 25}, {-1, 0});  // in front: bounces at x = 20.5
  e.run_collisions(1);
  EXPECT_NEAR(e.time(), 4.5, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[1].v.x, 1.0, kExact);
  e.run_until(10.0);
  EXPECT_NEAR(test::snapshot(e)[0].r.x, 25.0, kExact);
  EXPECT_EQ(e.stats().collisions, 1u);
}

TEST(EngineSurface, DiskPassesBeyondSegmentEnd) {
  EngineConfig c = test::open_space();
  c.walls = {{{20, 30}, {20, 10}, -1.0}};
  Engine e(c);
  e.add({25, 30.6}, {-1, 0});  // misses the end point (30) by 0.1
  e.run_until(10.0);
  EXPECT_EQ(e.stats().collisions, 0u);
}

TEST(EngineSurface, GrazingAndSimultaneousContactsInACorner) {
  // A disk sent exactly into a 90-degree corner touches both walls at the
  // same instant; it must come straight back, without overlap.
  Engine e(test::walled_box(10.0, 1.0));
  e.add({5, 5}, {-1, -1});
  e.run_until(20.0);
  const auto s = test::snapshot(e);
  EXPECT_LE(e.stats().max_overlap, kRoundOffOverlap);
  EXPECT_EQ(e.stats().recoveries, 0u);
  EXPECT_NEAR(std::abs(s[0].v.x), 1.0, kExact);
  EXPECT_NEAR(std::abs(s[0].v.y), 1.0, kExact);
}

// Inelastic disks under gravity in a V-shaped funnel: they slide into the
// wedge tip and pile up there. Never an overlap, never a disk through a wall.
TEST(EngineSurface, WedgeTipFunnelKeepsDisksOutOfWalls) {
  EngineConfig c = test::walled_box(30.0, 0.7);
  c.restitution = {0.7};
  c.tc = 1e-3;
  c.gravity = {0, -1};
  // V: from (0, 20) down to the tip (15, 5), up to (30, 20). Gas above.
  c.walls.push_back({{0, 20}, {15, 5}, -1.0});   // normal (1, 1)/sqrt2
  c.walls.push_back({{15, 5}, {30, 20}, -1.0});   // normal (-1, 1)/sqrt2
  Engine e(c);
  int added = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 14; ++i)
      if (e.try_add({1.5 + 2.0 * i, 21.0 + 1.05 * j}, {0.3 * ((i * 7 + j * 3) % 5 - 2), 0})) ++added;
  ASSERT_GT(added, 100);
  e.run_collisions(200000);
  const Stats st = e.stats();
  EXPECT_LE(st.max_overlap, kRoundOffOverlap);
  EXPECT_EQ(st.recoveries, 0u);
  e.for_each_particle([&](Vec2 r, Vec2) {
    // Above both wedge faces by at least a radius (less round-off).
    const double d1 = (r.x - 15.0) * (-std::sqrt(0.5)) + (r.y - 5.0) * std::sqrt(0.5);
    const double d2 = (r.x - 15.0) * std::sqrt(0.5) + (r.y - 5.0) * std::sqrt(0.5);
    EXPECT_GE(std::min(d1, d2), 0.5 - kRoundOffOverlap);
  });
}

}  // namespace
}  // namespace granular
