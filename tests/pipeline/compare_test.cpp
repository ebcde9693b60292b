// Speed against error: equal-error interpolation and the uniform match.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/compare.hpp"

using pipeline::GridRun;

namespace {
GridRun run(const char* fam, double level, double t, double err) {
  GridRun r;
  r.family = fam;
  r.level = level;
  r.cfd_wall_seconds = t;
  r.error = err;
  return r;
}
}  // namespace

TEST(Compare, SpeedupInterpolatesTheUniformCurveInLogLog) {
  // Uniform: error halves as time quadruples; clustered reaches 0.5 deg in 2 s.
  const std::vector<GridRun> u{run("uniform", 4, 1, 2.0), run("uniform", 2, 4, 1.0), run("uniform", 1, 16, 0.25)};
  const std::vector<GridRun> c{run("clustered", 4, 0.5, 1.0), run("clustered", 1, 2, 0.5)};
  const auto cmp = pipeline::compare(c, u, 1.0);
  EXPECT_EQ(cmp.clustered_pick, 1);
  // log-log between (4 s, 1.0) and (16 s, 0.25): error 0.5 at t = 8 s.
  EXPECT_NEAR(cmp.speedup_cfd, 8.0 / 2.0, 1e-12);
  EXPECT_NEAR(cmp.speedup_total, 8.0 / 3.0, 1e-12);  // + 1 s granular
  EXPECT_EQ(cmp.uniform_pick, 2);                     // coarsest uniform as accurate: h = 1
  EXPECT_TRUE(cmp.uniform_matches);
  EXPECT_TRUE(std::isnan(cmp.speedup_bound));
}

TEST(Compare, UniformNeverAsAccurateGivesALowerBound) {
  const std::vector<GridRun> u{run("uniform", 2, 4, 1.0), run("uniform", 1, 16, 0.5)};
  const std::vector<GridRun> c{run("clustered", 1, 2, 0.1)};
  const auto cmp = pipeline::compare(c, u, 0.0);
  EXPECT_TRUE(std::isnan(cmp.speedup_cfd));
  EXPECT_NEAR(cmp.speedup_bound, 8.0, 1e-12);
  EXPECT_EQ(cmp.uniform_pick, 1);  // the finest uniform grid
  EXPECT_FALSE(cmp.uniform_matches);
}

TEST(Compare, ScoreAgainstAngleAndStandoffReferences) {
  pipeline::Reference angle{"shock_angle_deg", "theta-beta-Mach", 27.38, 2.054};
  GridRun r = run("uniform", 1, 1, 0);
  r.value = 27.0;
  r.wall_pressure_ratio = 2.0;
  pipeline::score(r, angle);
  EXPECT_NEAR(r.error, 0.38, 1e-12);
  EXPECT_NEAR(r.pressure_error, 0.054 / 2.054, 1e-12);
  pipeline::Reference standoff{"standoff", "Billig", 0.5, NAN};
  r.value = 0.55;
  pipeline::score(r, standoff);
  EXPECT_NEAR(r.error, 0.1, 1e-12);
  EXPECT_TRUE(std::isnan(r.pressure_error));
}
