// Does shockfit's 95% angle interval mean what it says? Independent granular
// runs of one small wedge (fixed seeds) stand in for repeated experiments:
// each run's interval (from the spread of its averaging groups, as the
// pipeline reports it) should cover the mean of all runs (the run-to-run
// truth) about 95% of the time, and be about as wide as 1.96 run-to-run
// standard deviations. Slow: a few dozen CPU seconds.
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
// A run of this small scene may now and then see no clean attached shock
// (a noisy stagnation line); most must.
constexpr double kMinAttachedFraction = 0.9;
constexpr double kZ95 = 1.959963984540054;

struct SeedAngle {
  double angle_deg, half_width_deg, bootstrap_half_width_deg;
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

TEST(Coverage, WedgeAngleIntervalCoversSeedToSeedTruth) {
  scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/tests/data/wedge_coverage.yaml");
  const fs::path root =
      fs::temp_directory_path() / ("shockfit_coverage_" + std::to_string(::getpid()));
  std::vector<SeedAngle> runs;
  for (int k = 0; k < kSeeds; ++k) {
    s.granular.seed = static_cast<std::uint64_t>(kFirstSeed + k);
    granular::RunOptions o;
    o.out_dir = (root / std::to_string(k)).string();
    const granular::FlowResult g = granular::run_flow_scene(s, o);
    shockfit::ShockResult r = shockfit::locate_shock(s, g.fields);
    const double bootstrap = r.shock_angle_ci_deg;
    shockfit::apply_group_interval(s, g.groups, r);
    if (r.shock != scene::ShockKind::attached) continue;
    EXPECT_EQ(r.interval_method, "groups")
        << "seed " << s.granular.seed << ": " << g.groups.size() << " groups";
    runs.push_back({r.shock_angle_deg, r.shock_angle_ci_deg, bootstrap});
  }
  fs::remove_all(root);
  ASSERT_GE(static_cast<double>(runs.size()), kMinAttachedFraction * kSeeds);

  const auto n = static_cast<double>(runs.size());
  const double mean =
      std::accumulate(runs.begin(), runs.end(), 0.0,
                      [](double a, const SeedAngle& r) { return a + r.angle_deg; }) /
      n;
  double ss = 0.0;
  for (const SeedAngle& r : runs) ss += (r.angle_deg - mean) * (r.angle_deg - mean);
  const double sd = std::sqrt(ss / (n - 1.0));
  const auto covered = std::count_if(runs.begin(), runs.end(), [&](const SeedAngle& r) {
    return std::abs(r.angle_deg - mean) <= r.half_width_deg;
  });
  const double coverage = static_cast<double>(covered) / n;
  std::vector<double> hw, hw_bootstrap;
  for (const SeedAngle& r : runs) {
    hw.push_back(r.half_width_deg);
    hw_bootstrap.push_back(r.bootstrap_half_width_deg);
  }
  const double median_hw = median(hw);
  const auto covered_bootstrap = std::count_if(runs.begin(), runs.end(), [&](const SeedAngle& r) {
    return std::abs(r.angle_deg - mean) <= r.bootstrap_half_width_deg;
  });
  RecordProperty("coverage", std::to_string(coverage));
  std::printf(
      "coverage %.3f over %zu attached of %d seeds: mean %.3f deg, sd %.3f deg (1.96 sd %.3f), "
      "median "
      "half-width %.3f deg; the bootstrap over stations: coverage %.3f, median half-width %.3f "
      "deg\n",
      coverage, runs.size(), kSeeds, mean, sd, kZ95 * sd, median_hw,
      static_cast<double>(covered_bootstrap) / n, median(hw_bootstrap));
  EXPECT_GE(coverage, kMinCoverage);
  EXPECT_LE(coverage, kMaxCoverage);
  EXPECT_LT(median_hw, kWidthFactor * kZ95 * sd);
  EXPECT_GT(median_hw, kZ95 * sd / kWidthFactor);
}
