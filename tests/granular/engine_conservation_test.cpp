// Conservation laws to round-off: energy (e = 1) over 10^6 collisions,
// momentum in periodic boxes; determinism for a seed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine_support.hpp"

namespace granular {
namespace {

// Issue 3: e = 1 kinetic energy conserved to 1e-10 relative over 10^6 collisions.
constexpr double kEnergyTolerance = 1e-10;
// Total momentum of N unit masses with |v| ~ 1 drifts by round-off only.
constexpr double kMomentumPerParticle = 1e-12;
constexpr double kRoundOffOverlap = 1e-10;
constexpr std::uint64_t kSeed = 7;

TEST(EngineConservation, ElasticEnergyAndMomentumOverMillionCollisions) {
  SCOPED_TRACE("seed 7");
  const int n = 2000;
  Engine e = test::melted_box(n, 0.3, 0.0, kSeed);
  const double e0 = test::kinetic_energy(e);
  const Vec2 p0 = test::momentum(e);
  e.run_collisions(1000000);
  const Stats st = e.stats();
  EXPECT_EQ(st.collisions, 1000000u);
  EXPECT_NEAR(test::kinetic_energy(e) / e0, 1.0, kEnergyTolerance);
  const Vec2 p1 = test::momentum(e);
  EXPECT_NEAR(p1.x, p0.x, kMomentumPerParticle * n);
  EXPECT_NEAR(p1.y, p0.y, kMomentumPerParticle * n);
  EXPECT_LE(st.max_overlap, kRoundOffOverlap);
  EXPECT_EQ(st.recoveries, 0u);
}

TEST(EngineConservation, ElasticEnergyInWalledBoxWithGravity) {
  // With gravity the conserved quantity is kinetic + potential energy.
  EngineConfig c = test::walled_box(30.0, 1.0);
  c.gravity = {0.1, -0.5};
  Engine e(c);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i)
      e.add({2.0 + 2.2 * i, 2.0 + 2.2 * j}, {std::cos(i * 1.3 + j), std::sin(i * 0.7 - j * 2.1)});
  auto total = [&] {
    double t = 0;
    e.for_each_particle([&](Vec2 r, Vec2 v) { t += 0.5 * norm2(v) - dot(c.gravity, r); });
    return t;
  };
  const double e0 = total();
  e.run_collisions(300000);
  EXPECT_NEAR(total() / e0, 1.0, kEnergyTolerance);
  EXPECT_LE(e.stats().max_overlap, kRoundOffOverlap);
  EXPECT_EQ(e.stats().recoveries, 0u);
}

TEST(EngineConservation, SameSeedSameRun) {
  Engine a = test::melted_box(500, 0.35, 20.0, kSeed);
  Engine b = test::melted_box(500, 0.35, 20.0, kSeed);
  const auto sa = test::snapshot(a), sb = test::snapshot(b);
  ASSERT_EQ(sa.size(), sb.size());
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(sa[0])), 0);
  EXPECT_EQ(a.time(), b.time());
  Engine c = test::melted_box(500, 0.35, 20.0, kSeed + 1);
  EXPECT_NE(test::snapshot(c)[0].r.x, sa[0].r.x);
}

}  // namespace
}  // namespace granular
