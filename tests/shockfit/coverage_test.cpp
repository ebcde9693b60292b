// Does shockfit's 95% interval mean what it says? Independent granular runs
// of one small scene (fixed seeds) stand in for repeated experiments: each
// run's interval (from the spread of its averaging groups, as the pipeline
// reports it) should cover the mean of all runs (the run-to-run truth) about
// 95% of the time, and be about as wide as 1.96 run-to-run standard
// deviations. An attached wedge's angle and a disc's bow-shock standoff.
// Slow: a few dozen CPU seconds each.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "granular/flow_run.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"
#include "shockfit/group_interval.hpp"
#include "shockfit/locate.hpp"

namespace {

namespace fs = std::filesystem;

constexpr int kFirstSeed = 1;
constexpr int kSeeds = 24;
// Coverage of the mean of seeds by each seed's interval: a 95% interval
// over 24 seeds covers 21-24 of them with high probability.
constexpr double kMinCoverage = 0.85;
constexpr double kMaxCoverage = 1.0;
// Median half-width against 1.96 x the run-to-run standard deviation (the
// sd of 24 runs is itself uncertain by about 15%).
constexpr double kWidthFactor = 1.5;
// A run of these small scenes may now and then see no clean shock of the
// expected kind (a noisy stagnation line); most must.
constexpr double kMinFoundFraction = 0.9;
constexpr double kZ95 = 1.959963984540054;

// One run's value (angle, deg, or standoff, body lengths) with its groups'
// and its bootstrap's 95% half-widths.
struct SeedValue {
  double value, half_width, bootstrap_half_width;
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double value_of(const shockfit::ShockResult& r) {
  return r.shock == scene::ShockKind::attached ? r.shock_angle_deg : r.standoff;
}

double half_width_of(const shockfit::ShockResult& r) {
  return r.shock == scene::ShockKind::attached ? r.shock_angle_ci_deg : r.standoff_ci;
}

// kSeeds granular runs of the scene, each fitted with the groups' interval;
// the runs that find a shock of `kind`.
std::vector<SeedValue> run_seeds(const std::string& scene_file, scene::ShockKind kind) {
  scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/tests/data/" + scene_file);
  const fs::path root =
      test_support::scratch_root() / ("shockfit_coverage_" + std::to_string(::getpid()));
  std::vector<SeedValue> runs;
  for (int k = 0; k < kSeeds; ++k) {
    s.granular.seed = static_cast<std::uint64_t>(kFirstSeed + k);
    granular::RunOptions o;
    o.out_dir = (root / std::to_string(k)).string();
    const granular::FlowResult g = granular::run_flow_scene(s, o);
    shockfit::ShockResult r = shockfit::locate_shock(s, g.fields);
    const double bootstrap = half_width_of(r);
    shockfit::apply_group_interval(s, g.groups, r);
    if (r.shock != kind) continue;
    EXPECT_EQ(r.interval_method, "groups")
        << "seed " << s.granular.seed << ": " << g.groups.size() << " groups";
    runs.push_back({value_of(r), half_width_of(r), bootstrap});
  }
  fs::remove_all(root);
  return runs;
}

double coverage_of(const std::vector<SeedValue>& runs, double mean, bool bootstrap) {
  const auto covered = std::count_if(runs.begin(), runs.end(), [&](const SeedValue& r) {
    return std::abs(r.value - mean) <= (bootstrap ? r.bootstrap_half_width : r.half_width);
  });
  return static_cast<double>(covered) / static_cast<double>(runs.size());
}

void expect_coverage(const std::vector<SeedValue>& runs, const char* what) {
  ASSERT_GE(static_cast<double>(runs.size()), kMinFoundFraction * kSeeds);
  const auto n = static_cast<double>(runs.size());
  const double mean = std::accumulate(runs.begin(), runs.end(), 0.0,
                                      [](double a, const SeedValue& r) { return a + r.value; }) /
                      n;
  double ss = 0.0;
  for (const SeedValue& r : runs) ss += (r.value - mean) * (r.value - mean);
  const double sd = std::sqrt(ss / (n - 1.0));
  std::vector<double> hw, hw_bootstrap;
  for (const SeedValue& r : runs) {
    hw.push_back(r.half_width);
    hw_bootstrap.push_back(r.bootstrap_half_width);
  }
  const double coverage = coverage_of(runs, mean, false);
  const double median_hw = median(hw);
  ::testing::Test::RecordProperty("coverage", std::to_string(coverage));
  std::printf(
      "%s: coverage %.3f over %zu of %d seeds: mean %.4f, sd %.4f (1.96 sd %.4f), median "
      "half-width %.4f; the bootstrap over stations: coverage %.3f, median half-width %.4f\n",
      what, coverage, runs.size(), kSeeds, mean, sd, kZ95 * sd, median_hw,
      coverage_of(runs, mean, true), median(hw_bootstrap));
  EXPECT_GE(coverage, kMinCoverage) << what;
  EXPECT_LE(coverage, kMaxCoverage) << what;
  EXPECT_LT(median_hw, kWidthFactor * kZ95 * sd) << what;
  EXPECT_GT(median_hw, kZ95 * sd / kWidthFactor) << what;
}

}  // namespace

TEST(Coverage, WedgeAngleIntervalCoversSeedToSeedTruth) {
  expect_coverage(run_seeds("wedge_coverage.yaml", scene::ShockKind::attached), "wedge angle");
}

TEST(Coverage, DiscStandoffIntervalCoversSeedToSeedTruth) {
  expect_coverage(run_seeds("disc_coverage.yaml", scene::ShockKind::detached), "disc standoff");
}
