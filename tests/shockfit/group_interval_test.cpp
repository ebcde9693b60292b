// The interval from the averaging groups' spread, on fields with known
// shocks: each group's shock a known angle off the pooled one.
#include "shockfit/group_interval.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"
#include "shockfit/locate.hpp"
#include "shockfit/shock_line.hpp"
#include "synthetic.hpp"

namespace {

using scene::kDeg;

scene::Scene wedge_scene() {
  return scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n");
}

// A granular-like lattice (volume fraction and v) with a tanh shock at
// angle beta through the apex, a few cells wide.
scene::Lattice shock_at(const scene::Scene& s, double beta) {
  const double h = 0.005, width = 2 * h;
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  auto behind = [&](double x, double y) {
    return 0.5 * (1.0 - std::tanh((y * std::cos(beta) - x * std::sin(beta)) / width));
  };
  shockfit_test::fill(
      lat, "volume_fraction", [&](double x, double y) { return 0.1 * (1.0 + 2.0 * behind(x, y)); },
      0.0, 1);
  shockfit_test::fill(
      lat, "v", [&](double x, double y) { return 0.5 * behind(x, y); }, 0.0, 2);
  return lat;
}

// A group's fields with no jump anywhere: no shock found on them.
scene::Lattice blank_lattice(const scene::Scene& s) {
  scene::Lattice blank = shockfit_test::domain_lattice(s, 0.005);
  blank.add("volume_fraction", std::nan(""));
  blank.add("v", std::nan(""));
  return blank;
}

}  // namespace

TEST(GroupInterval, StudentQuantiles) {
  EXPECT_NEAR(shockfit::student_t95(1), 12.706, 1e-3);
  EXPECT_NEAR(shockfit::student_t95(7), 2.365, 1e-3);
  EXPECT_NEAR(shockfit::student_t95(30), 2.042, 1e-3);
  EXPECT_NEAR(shockfit::student_t95(60), 2.000, 2e-3);
  EXPECT_NEAR(shockfit::student_t95(1000), 1.962, 2e-3);
  EXPECT_TRUE(std::isinf(shockfit::student_t95(0)));
}

TEST(GroupInterval, HalfWidthIsStudentTimesTheGroupsStandardError) {
  // Eight groups whose shocks stand +-0.4 and +-0.8 deg off the pooled
  // angle: sd 0.676 deg (n - 1), standard error 0.239, half-width 2.365 x
  // that = 0.565 deg. The locator resolves each group's angle to a few
  // hundredths of a degree on this lattice, hence the tolerance.
  const scene::Scene s = wedge_scene();
  const double beta = *scene::oblique_shock_beta(3.0, 10.0 * kDeg, 1.4);
  shockfit::ShockResult r = shockfit::locate_shock(s, shock_at(s, beta));
  ASSERT_EQ(r.shock, scene::ShockKind::attached);
  EXPECT_EQ(r.interval_method, "bootstrap");
  const double offsets[] = {0.4, -0.4, 0.8, -0.8, 0.4, -0.4, 0.8, -0.8};
  std::vector<scene::Lattice> groups;
  for (const double d : offsets) groups.push_back(shock_at(s, beta + d * kDeg));
  shockfit::apply_group_interval(s, groups, r);
  EXPECT_EQ(r.interval_method, "groups");
  EXPECT_EQ(r.interval_groups, 8);
  double ss = 0.0;
  for (const double d : offsets) ss += d * d;
  const double want = shockfit::student_t95(7) * std::sqrt(ss / 7.0 / 8.0);
  constexpr double kRelTol = 0.1;
  EXPECT_NEAR(r.shock_angle_ci_deg, want, kRelTol * want);
  EXPECT_DOUBLE_EQ(r.shock_angle_hi_deg - r.shock_angle_lo_deg, 2.0 * r.shock_angle_ci_deg);
  EXPECT_EQ(r.summary()["interval_method"], "groups");
}

TEST(GroupInterval, TooFewGroupsFindingTheShockKeepTheBootstrap) {
  // Three groups with the shock and five blank ones (no jump anywhere):
  // fewer than kMinIntervalGroups values, so the bootstrap interval stays.
  const scene::Scene s = wedge_scene();
  const double beta = *scene::oblique_shock_beta(3.0, 10.0 * kDeg, 1.4);
  shockfit::ShockResult r = shockfit::locate_shock(s, shock_at(s, beta));
  const double bootstrap = r.shock_angle_ci_deg;
  std::vector<scene::Lattice> groups(3, shock_at(s, beta));
  groups.insert(groups.end(), 5, blank_lattice(s));
  shockfit::apply_group_interval(s, groups, r);
  EXPECT_EQ(r.interval_method, "bootstrap");
  EXPECT_EQ(r.interval_groups, 0);
  EXPECT_DOUBLE_EQ(r.shock_angle_ci_deg, bootstrap);
}

TEST(GroupInterval, AnAttachedAngleIsTheGroupsOwnFitsMean) {
  // Seven groups' shocks 0.3 deg steeper than the pooled fields' and one 6
  // deg steeper (another feature found): each group's own fit finds its
  // shock and is listed; the wild one is left out of the mean, so the angle
  // is the pooled one + 0.3, the pooled kept beside it and the reported line
  // turned with it. The interval stays the groups' refitted on the pooled
  // stations, wild one included: 2.365 x sd {0.3 x 7, 6.0} / sqrt(8).
  const scene::Scene s = wedge_scene();
  const double beta = *scene::oblique_shock_beta(3.0, 10.0 * kDeg, 1.4);
  shockfit::ShockResult r = shockfit::locate_shock(s, shock_at(s, beta));
  const double pooled = r.shock_angle_deg;
  std::vector<scene::Lattice> groups(7, shock_at(s, beta + 0.3 * kDeg));
  groups.push_back(shock_at(s, beta + 6.0 * kDeg));
  shockfit::apply_group_interval(s, groups, r);
  ASSERT_EQ(r.interval_method, "groups");
  ASSERT_EQ(r.group_own_angles.size(), 8u);
  // The locator resolves each angle to a few hundredths of a degree here.
  constexpr double kAngleTolDeg = 0.05;
  for (std::size_t k = 0; k < 7; ++k)
    EXPECT_NEAR(r.group_own_angles[k], pooled + 0.3, kAngleTolDeg);
  EXPECT_NEAR(r.group_own_angles[7], pooled + 6.0, 4 * kAngleTolDeg);
  EXPECT_DOUBLE_EQ(r.shock_angle_pooled_deg, pooled);
  EXPECT_NEAR(r.shock_angle_deg, pooled + 0.3, kAngleTolDeg);
  EXPECT_NEAR(std::atan2(r.line_dir.y, r.line_dir.x) / kDeg, r.shock_angle_deg, 1e-9);
  const double offsets[] = {0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 6.0};
  double mean = 0.0, ss = 0.0;
  for (const double d : offsets) mean += d / 8.0;
  for (const double d : offsets) ss += (d - mean) * (d - mean);
  const double want = shockfit::student_t95(7) * std::sqrt(ss / 7.0 / 8.0);
  constexpr double kRelTol = 0.1;
  EXPECT_NEAR(r.shock_angle_ci_deg, want, kRelTol * want);
  EXPECT_NEAR(0.5 * (r.shock_angle_hi_deg + r.shock_angle_lo_deg), r.shock_angle_deg, 1e-9);
  const nlohmann::json j = r.summary();
  EXPECT_EQ(j["group_own_angles_deg"].size(), 8u);
  EXPECT_DOUBLE_EQ(j["shock_angle_pooled_deg"].get<double>(), pooled);
  EXPECT_DOUBLE_EQ(j["shock_angle_deg"].get<double>(), r.shock_angle_deg);
}

TEST(GroupInterval, TooFewOwnFitsKeepThePooledAngle) {
  // Five groups with the shock 0.3 deg steeper and three blank ones: five
  // own fits of eight, fewer than three quarters, so the angle stays the
  // pooled fit's (also kept as shock_angle_pooled_deg) while the interval
  // still comes from the five groups.
  const scene::Scene s = wedge_scene();
  const double beta = *scene::oblique_shock_beta(3.0, 10.0 * kDeg, 1.4);
  shockfit::ShockResult r = shockfit::locate_shock(s, shock_at(s, beta));
  const double pooled = r.shock_angle_deg;
  std::vector<scene::Lattice> groups(5, shock_at(s, beta + 0.3 * kDeg));
  groups.insert(groups.end(), 3, blank_lattice(s));
  shockfit::apply_group_interval(s, groups, r);
  ASSERT_EQ(r.interval_method, "groups");
  EXPECT_EQ(r.interval_groups, 5);
  EXPECT_DOUBLE_EQ(r.shock_angle_deg, pooled);
  EXPECT_DOUBLE_EQ(r.shock_angle_pooled_deg, pooled);
}

// The outlier rule the groups and the bow shock's stations share: distances
// from the median (the mean of the middle two for an even count) in robust
// sigmas (1.4826 x the median absolute distance), never tighter than the floor.
TEST(NearMedian, KeepsTheBulkAndDropsAWildValueAboutTheTrueMedian) {
  // Even count: median 11 (the middle two, 11 and 11), median distance 1;
  // the wild 40 lies 29 away, beyond 3.5 x 1.4826.
  const std::vector<double> even{9, 10, 11, 12, 10, 11, 40, 11};
  const auto keep = shockfit::near_median(even, 3.5, 0.0);
  EXPECT_EQ(keep.size(), 7u);
  for (const std::size_t k : keep) EXPECT_NE(even[k], 40.0);
  // A floor wider than the wild value's distance keeps everything.
  EXPECT_EQ(shockfit::near_median(even, 3.5, 30.0).size(), even.size());
  // Odd count, identical values but one: zero spread, so only the floor
  // decides (0 here: the odd one goes).
  const std::vector<double> odd{2, 2, 2, 2, 3};
  EXPECT_EQ(shockfit::near_median(odd, 3.5, 0.0).size(), 4u);
  EXPECT_EQ(shockfit::near_median(odd, 3.5, 1.0).size(), 5u);
  EXPECT_TRUE(shockfit::near_median({}, 3.5, 0.0).empty());
}

namespace {

// Billig's bow shock ahead of the Mach 4 disc case study, moved `shift`
// upstream (scene units), tanh of one cell, no noise.
scene::Lattice bow_at(const scene::Scene& s, double shift) {
  const double mach = s.freestream.mach, R = s.body->radius;
  const double xv = -R - scene::billig_standoff_cylinder(mach) * R - shift;
  const double r2 = scene::oblique_density_ratio(mach, std::numbers::pi / 2, 1.4);
  const double h = 0.005;
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  auto dist = [&](double x, double y) {  // signed, downstream positive
    const double dy = 1e-6;
    const double slope =
        (scene::billig_shock_x(mach, R, y + dy) - scene::billig_shock_x(mach, R, y - dy)) /
        (2 * dy);
    return (x - xv - scene::billig_shock_x(mach, R, y)) / std::sqrt(1.0 + slope * slope);
  };
  shockfit_test::fill(
      lat, "volume_fraction",
      [&](double x, double y) {
        return 0.1 * (1.0 + (r2 - 1.0) * 0.5 * (1.0 + std::tanh(dist(x, y) / h)));
      },
      0.0, 1);
  return lat;
}

}  // namespace

TEST(GroupInterval, ABowShocksStandoffIsTheGroupsMean) {
  // Eight groups whose bow shock stands 2 or 4 cells farther off than the
  // pooled fields' (mean 3 cells): the standoff reported is the groups'
  // mean, the pooled fit's is kept beside it, the vertex moves with the
  // standoff, and the interval is Student's t times the groups' standard
  // error (offsets +-1 cell about their mean: sd 1.07 cells).
  const scene::Scene s =
      scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/disc_M4.yaml");
  const double h = 0.005, L = s.body->radius;  // a disc's body length is its radius
  shockfit::ShockResult r = shockfit::locate_shock(s, bow_at(s, 0.0));
  ASSERT_EQ(r.shock, scene::ShockKind::detached);
  const double pooled = r.standoff, vertex = r.vertex_x;
  const double offsets[] = {2, 4, 2, 4, 2, 4, 2, 4};  // cells
  std::vector<scene::Lattice> groups;
  for (const double k : offsets) groups.push_back(bow_at(s, k * h));
  shockfit::apply_group_interval(s, groups, r);
  ASSERT_EQ(r.interval_method, "groups");
  // The locator finds a noiseless tanh shock to a tenth of a cell.
  constexpr double kCellTol = 0.1;
  EXPECT_DOUBLE_EQ(r.standoff_pooled, pooled);
  EXPECT_NEAR(r.standoff, pooled + 3 * h / L, kCellTol * h / L);
  EXPECT_NEAR(r.vertex_x, vertex - 3 * h, kCellTol * h);
  const double want = shockfit::student_t95(7) * std::sqrt(8.0 / 7.0 / 8.0) * h / L;
  EXPECT_NEAR(r.standoff_ci, want, 0.1 * want);
  EXPECT_DOUBLE_EQ(r.summary()["standoff_pooled"].get<double>(), pooled);
}
