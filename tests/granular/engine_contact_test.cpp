// Exact collision times and post-collision velocities against hand-computed
// cases (disk-disk, unequal masses, restitution, TC model).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "engine_support.hpp"
#include "scene/errors.hpp"

namespace granular {
namespace {

// Hand-computed times and velocities are exact decimals; the engine's
// arithmetic may differ from them by a few ulps.
constexpr double kExact = 1e-12;

TEST(EngineContact, HeadOnElasticExchange) {
  Engine e(test::open_space());
  e.add({10, 20}, {1, 0});
  e.add({13, 20}, {-1, 0});
  e.run_collisions(1);
  // Gap 2 closes at relative speed 2.
  EXPECT_NEAR(e.time(), 1.0, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[0].v.x, -1.0, kExact);
  EXPECT_NEAR(s[1].v.x, 1.0, kExact);
  EXPECT_NEAR(s[1].r.x - s[0].r.x, 1.0, kExact);
}

TEST(EngineContact, ObliqueImpactOnDiskAtRest) {
  Engine e(test::open_space());
  e.add({0.5, 10}, {1, 0});
  e.add({5.5, 10.6}, {0, 0});
  e.run_collisions(1);
  // |(x - 5.5, -0.6)| = 1 at x = 4.7: t = 4.2; line of centres (-0.8, -0.6).
  EXPECT_NEAR(e.time(), 4.2, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[0].v.x, 0.36, kExact);
  EXPECT_NEAR(s[0].v.y, -0.48, kExact);
  EXPECT_NEAR(s[1].v.x, 0.64, kExact);
  EXPECT_NEAR(s[1].v.y, 0.48, kExact);
}

TEST(EngineContact, UnequalMassesWithRestitution) {
  EngineConfig c = test::open_space();
  c.species = {Species{0.5, 1.0}, Species{1.0, 3.0}};
  const double e_dd = 0.5;
  c.restitution = {1.0, e_dd, e_dd, 1.0};
  Engine e(c);
  e.add({10, 20}, {2, 0}, 0);
  e.add({14, 20}, {0, 0}, 1);
  e.run_collisions(1);
  // sigma = 1.5: gap 2.5 at speed 2: t = 1.25. Impulse (1+e) mu vn with
  // mu = 3/4: J = 2.25; v0 = 2 - 2.25 = -0.25, v1 = 2.25 / 3 = 0.75.
  EXPECT_NEAR(e.time(), 1.25, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[0].v.x, -0.25, kExact);
  EXPECT_NEAR(s[1].v.x, 0.75, kExact);
}

TEST(EngineContact, TcModelMakesRepeatedCollisionsElastic) {
  // Three disks in a row: the middle one is hit at t = 1 and again,
  // by its other neighbour, within tc: the second collision is elastic.
  EngineConfig c = test::open_space();
  c.restitution = {0.5};
  c.tc = 1.0;
  Engine e(c);
  e.add({10, 20}, {1, 0});
  e.add({12, 20}, {0, 0});
  e.add({13.25, 20}, {0, 0});
  e.run_collisions(1);
  EXPECT_NEAR(e.time(), 1.0, kExact);
  // e = 0.5: v0 = 0.25, v1 = 0.75; v1 reaches the third disk after 0.25/0.75.
  e.run_collisions(1);
  EXPECT_NEAR(e.time(), 1.0 + 0.25 / 0.75, kExact);
  const auto s = test::snapshot(e);
  EXPECT_NEAR(s[1].v.x, 0.0, kExact);  // elastic exchange (TC)
  EXPECT_NEAR(s[2].v.x, 0.75, kExact);
}

// A speed-dependent restitution: an impact slower than elastic_below
// bounces elastically, a faster one loses energy as its restitution says.
TEST(EngineContact, SlowImpactsAreElasticBelowTheThreshold) {
  const auto after = [](double speed) {
    EngineConfig c = test::open_space();
    c.restitution = {0.5};
    c.elastic_below = 3.0;
    Engine e(c);
    e.add({10, 20}, {0.5 * speed, 0});
    e.add({13, 20}, {-0.5 * speed, 0});
    e.run_collisions(1);
    return test::snapshot(e)[1].v.x;  // rebound speed of the second disk
  };
  EXPECT_NEAR(after(2.9), 0.5 * 2.9, kExact);        // elastic
  EXPECT_NEAR(after(4.0), 0.5 * 0.5 * 4.0, kExact);  // e = 0.5
}

TEST(EngineContact, PeriodicImageCollision) {
  Engine e(test::open_space(10.0));
  e.add({0.75, 5}, {-1, 0});
  e.add({9.25, 5}, {1, 0});
  e.run_collisions(1);
  // Image distance 1.5, gap 0.5 at relative speed 2.
  EXPECT_NEAR(e.time(), 0.25, kExact);
  EXPECT_NEAR(test::snapshot(e)[0].v.x, 1.0, kExact);
}

TEST(EngineContact, OverlappingParticlesAreAClearError) {
  Engine e(test::open_space());
  e.add({10, 10}, {0, 0});
  try {
    e.add({10.5, 10}, {0, 0});
    FAIL() << "overlap accepted";
  } catch (const scene::InputError& err) {
    EXPECT_STREQ(err.what(),
                 "granular engine: particle at (10.5, 10) overlaps another particle or a wall, or "
                 "lies outside the box");
  }
}

TEST(EngineContact, DomainBeyondTheCellLimitIsAClearError) {
  // Cells are named by 16-bit columns and 15-bit rows.
  EngineConfig c = test::open_space(10.0);
  c.xmax = 40000.0;
  c.left = c.right = c.bottom = c.top = Face::closed;
  try {
    Engine e(c);
    FAIL() << "a domain 40000 diameters long was accepted";
  } catch (const scene::InputError& err) {
    EXPECT_NE(std::string(err.what()).find("40000 cells"), std::string::npos) << err.what();
  }
  // Far beyond the int range: refused by the same check, before any cast.
  c.xmax = 1e12;
  try {
    Engine e(c);
    FAIL() << "a domain 1e12 diameters long was accepted";
  } catch (const scene::InputError& err) {
    EXPECT_NE(std::string(err.what()).find("1000000000000 cells"), std::string::npos) << err.what();
  }
  c.xmax = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Engine{c}, scene::InputError);
}

TEST(EngineContact, SmallPeriodicBoxIsRejected) {
  try {
    Engine e(test::open_space(2.5));
    FAIL() << "accepted";
  } catch (const scene::InputError& err) {
    EXPECT_STREQ(err.what(), "granular engine: a periodic side must be at least 3 largest diameters long");
  }
}

}  // namespace
}  // namespace granular
