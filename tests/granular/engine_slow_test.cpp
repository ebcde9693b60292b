// Slow: zero overlaps over 10^7 collisions of a dense inelastic flow under
// gravity into a wedge tip (a V-shaped hopper whose disks are stirred by a
// sharp convex wedge standing in it).
#include <gtest/gtest.h>

#include <cmath>

#include "engine_support.hpp"

namespace granular {
namespace {

constexpr double kRoundOffOverlap = 1e-10;

TEST(EngineSlow, NoOverlapsInDenseInelasticWedgeFlow) {
  EngineConfig c = test::walled_box(40.0, 0.8);
  c.left = c.right = Face::periodic;  // gas re-enters: a steady flow
  c.walls = {{{0, 0}, {40, 0}, -1.0}, {{40, 40}, {0, 40}, -1.0}};
  c.restitution = {0.8};
  c.tc = 1e-3;
  c.gravity = {0.3, -1.0};
  // A sharp wedge (convex tip pointing up-stream at (15, 12)) on the floor.
  const Vec2 tip{15, 12}, base0{10, 0}, base1{25, 0};
  c.walls.push_back({base0, tip, -1.0});
  c.walls.push_back({tip, base1, -1.0});
  c.vertices = {{tip, -1.0}};
  Engine e(c);
  int added = 0;
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 36; ++i)
      if (e.try_add({0.6 + 1.1 * i, 13.0 + 1.1 * j}, {std::cos(i * 2.1 + j), std::sin(i * 0.9 - j)})) ++added;
  ASSERT_GT(added, 800);
  e.run_collisions(10000000);
  const Stats st = e.stats();
  EXPECT_EQ(st.collisions, 10000000u);
  EXPECT_LE(st.max_overlap, kRoundOffOverlap);
  EXPECT_EQ(st.recoveries, 0u);
}

}  // namespace
}  // namespace granular
