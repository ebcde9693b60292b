// The work price: a machine's cost per cell-step fitted on a run's timings,
// and the verdict priced by it (work_price.hpp, verdict.hpp).
#include "pipeline/work_price.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "pipeline/rejudge.hpp"
#include "pipeline/verdict.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

namespace {
using pipeline::VerdictRun;
using pipeline::WorkRun;

// A machine charging 2 ms per step + 1.5 us per cell-step, meshing 1 s + 100 us per cell.
constexpr double kPerStep = 2e-3, kPerCellStep = 1.5e-6, kMeshBase = 1.0, kMeshPerCell = 1e-4;

WorkRun exact_run(long cells, long steps) {
  return {cells, steps, static_cast<double>(steps) * (kPerStep + kPerCellStep * static_cast<double>(cells)),
          kMeshBase + kMeshPerCell * static_cast<double>(cells)};
}

// Two families on this machine: error = 0.1 (cells / 1000)^-0.5 (uniform)
// and the clustered family reaching each error with 1/4 of the cells; steps
// grow like sqrt(cells). One timing of each run scatters by `noise` (log sd).
struct Families {
  std::vector<VerdictRun> uniform, clustered;
};
Families families(double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Families f;
  for (const long cells : {1000L, 2000L, 4000L, 8000L, 16000L}) {
    for (const bool clustered : {false, true}) {
      const long n = clustered ? cells / 4 : cells;
      const long steps = std::lround(20.0 * std::sqrt(static_cast<double>(n)));
      const WorkRun w = exact_run(n, steps);
      const double error = 0.1 * std::pow(static_cast<double>(cells) / 1000.0, -0.5);
      VerdictRun r{clustered ? "clustered" : "uniform",
                   1000.0 / static_cast<double>(cells),
                   n,
                   steps,
                   w.cfd_cpu * std::exp(noise * normal(rng)),
                   w.mesh_cpu * std::exp(noise * normal(rng)),
                   error,
                   0.0,
                   true,
                   ""};
      (clustered ? f.clustered : f.uniform).push_back(r);
    }
  }
  return f;
}

const pipeline::PrimaryError kPrimary{"l1_density", "exact", "test"};
constexpr double kPredictorCpu = 0.5;

}  // namespace

TEST(WorkPrice, RecoversTheMachineFromExactTimings) {
  std::vector<WorkRun> runs;
  for (const long cells : {500L, 1000L, 3000L, 9000L}) runs.push_back(exact_run(cells, 100 + cells / 10));
  const auto p = pipeline::fit_work_price(runs);
  ASSERT_TRUE(p.ok);
  EXPECT_NEAR(p.per_step, kPerStep, 1e-9);
  EXPECT_NEAR(p.per_cell_step, kPerCellStep, 1e-12);
  EXPECT_NEAR(p.mesh_base, kMeshBase, 1e-9);
  EXPECT_NEAR(p.mesh_per_cell, kMeshPerCell, 1e-12);
  EXPECT_NEAR(p.cfd_log_sd, 0.0, 1e-9);
  EXPECT_NEAR(p.cfd(runs[2]), runs[2].cfd_cpu, 1e-9 * runs[2].cfd_cpu);
}

TEST(WorkPrice, ScatterOfOneTimingIsMeasuredAndCoefficientsStayPhysical) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  constexpr double kNoise = 0.2;
  std::vector<WorkRun> runs;
  for (int k = 0; k < 40; ++k) {
    WorkRun r = exact_run(500 + 400 * k, 300 + 37 * k);
    r.cfd_cpu *= std::exp(kNoise * normal(rng));
    runs.push_back(r);
  }
  const auto p = pipeline::fit_work_price(runs);
  ASSERT_TRUE(p.ok);
  EXPECT_NEAR(p.cfd_log_sd, kNoise, 0.06);  // 40 draws: the sd is known to about 0.2/sqrt(80)*2
  EXPECT_NEAR(p.per_cell_step, kPerCellStep, 0.25 * kPerCellStep);
  EXPECT_GE(p.per_step, 0.0);
  // Fewer than three usable runs: no price.
  EXPECT_FALSE(pipeline::fit_work_price({runs[0], runs[1]}).ok);
  EXPECT_FALSE(pipeline::fit_work_price({runs[0], runs[1], {0, 0, 1.0, 1.0}}).ok);
}

TEST(PricedVerdict, ExactTimingsGiveTheWorkRatio) {
  const Families f = families(0.0, 1);
  const auto v = pipeline::make_verdict(kPrimary, f.clustered, f.uniform, kPredictorCpu);
  ASSERT_TRUE(v.priced);
  // At the clustered finest error (16000 uniform-equivalent cells) the uniform
  // family needs its 16000-cell run, the clustered one its 4000-cell run.
  const WorkRun u = exact_run(16000, std::lround(20.0 * std::sqrt(16000.0)));
  const WorkRun c = exact_run(4000, std::lround(20.0 * std::sqrt(4000.0)));
  // The fits are straight lines through five exact points of a nearly
  // power-law family: the read-off is within a few percent of the work ratio.
  constexpr double kFitTolerance = 0.05;
  EXPECT_NEAR(v.speedup_cfd.value, u.cfd_cpu / c.cfd_cpu, kFitTolerance * u.cfd_cpu / c.cfd_cpu);
  EXPECT_EQ(v.verdict_cfd, "faster");
}

TEST(PricedVerdict, AClusteredErrorBelowEveryUniformGridIsReadInsideBothRanges) {
  // Without the uniform 16000-cell run, the clustered finest error lies below
  // every uniform grid's: the headline reads the uniform finest's error (the
  // 8000-cell run against the clustered 2000-cell one), inside both ranges,
  // and the reading at the clustered finest (extrapolated) is kept beside it.
  Families f = families(0.0, 1);
  f.uniform.pop_back();
  const auto v = pipeline::make_verdict(kPrimary, f.clustered, f.uniform, kPredictorCpu);
  ASSERT_TRUE(v.priced);
  EXPECT_DOUBLE_EQ(v.target_error, f.uniform.back().error);
  EXPECT_FALSE(v.extrapolated);
  EXPECT_DOUBLE_EQ(v.beyond_uniform.error, f.clustered.back().error);
  const WorkRun u = exact_run(8000, std::lround(20.0 * std::sqrt(8000.0)));
  const WorkRun c = exact_run(2000, std::lround(20.0 * std::sqrt(2000.0)));
  // Read at the uniform fit's end, where a straight line through the slightly
  // curved family (a fixed cost per step) strays most: 15%.
  constexpr double kEndTolerance = 0.15;
  EXPECT_NEAR(v.speedup_cfd.value, u.cfd_cpu / c.cfd_cpu, kEndTolerance * u.cfd_cpu / c.cfd_cpu);
  EXPECT_TRUE(std::isfinite(v.beyond_uniform.speedup_cfd.value));
  EXPECT_NE(v.note.find("inside both families' ranges"), std::string::npos);
  const nlohmann::json j = pipeline::verdict_json(v);
  EXPECT_DOUBLE_EQ(j["beyond_uniform_range"]["target_error"].get<double>(), v.beyond_uniform.error);
  // With the uniform finest run back, nothing moves.
  const Families all = families(0.0, 1);
  const auto w = pipeline::make_verdict(kPrimary, all.clustered, all.uniform, kPredictorCpu);
  EXPECT_DOUBLE_EQ(w.target_error, all.clustered.back().error);
  EXPECT_TRUE(std::isnan(w.beyond_uniform.error));
  EXPECT_TRUE(pipeline::verdict_json(w)["beyond_uniform_range"].is_null());
}

TEST(PricedVerdict, TwoNoisyTimingsOfTheSameRunsAgree) {
  // The same grids timed twice with 30% scatter per timing: the measured
  // ratios move, the priced ones much less, and the verdicts agree.
  constexpr double kNoise = 0.3;
  const Families a = families(kNoise, 11), b = families(kNoise, 12);
  const auto va = pipeline::make_verdict(kPrimary, a.clustered, a.uniform, kPredictorCpu);
  const auto vb = pipeline::make_verdict(kPrimary, b.clustered, b.uniform, kPredictorCpu);
  ASSERT_TRUE(va.priced && vb.priced);
  const double priced = std::abs(std::log(va.speedup_cfd.value / vb.speedup_cfd.value));
  const double measured = std::abs(std::log(va.measured_cfd.value / vb.measured_cfd.value));
  EXPECT_LT(priced, 0.5 * measured) << "priced " << priced << " measured " << measured;
  EXPECT_EQ(va.verdict_cfd, vb.verdict_cfd);
  // The interval carries the timing scatter: it contains the exact work ratio.
  const double exact = pipeline::make_verdict(kPrimary, families(0.0, 1).clustered, families(0.0, 1).uniform,
                                              kPredictorCpu)
                           .speedup_cfd.value;
  EXPECT_LT(va.speedup_cfd.ci_low, exact);
  EXPECT_GT(va.speedup_cfd.ci_high, exact);
}

TEST(PricedVerdict, RunsWithoutStepsFallBackToMeasuredTimings) {
  Families f = families(0.0, 1);
  for (auto& r : f.uniform) r.steps = 0;
  const auto v = pipeline::make_verdict(kPrimary, f.clustered, f.uniform, kPredictorCpu);
  EXPECT_FALSE(v.priced);
  EXPECT_DOUBLE_EQ(v.speedup_total.value, v.measured_total.value);
  EXPECT_NE(v.note.find("measured single timings"), std::string::npos);
}

TEST(Rejudge, MissingOrMalformedSummaryIsAnInputErrorNamingTheFile) {
  const std::string dir = test_support::fresh_dir("rejudge_bad");
  EXPECT_THROW(pipeline::rejudge_summary(dir + "/none.json"), scene::InputError);
  scene::write_file_atomic(dir + "/summary.json", "{\"runs\": [{\"family\": \"uniform\", \"level\": 1}]}");
  try {
    pipeline::rejudge_summary(dir + "/summary.json");
    FAIL() << "a run without cells was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/summary.json: runs[0]: key 'cells'"), std::string::npos) << e.what();
  }
}

TEST(PricedVerdict, CalibrationIsASeparateLineThatLowersTheTotalWhenChargedAlone) {
  const Families f = families(0.0, 1);
  auto v = pipeline::make_verdict(kPrimary, f.clustered, f.uniform, kPredictorCpu);
  const double before = v.speedup_total.value;
  pipeline::charge_calibration(v, f.clustered, f.uniform, std::nan(""), 5);
  EXPECT_TRUE(std::isnan(v.calibration.cpu_seconds)) << "no table, no line";
  constexpr double kCalibrationCpu = 100.0;
  pipeline::charge_calibration(v, f.clustered, f.uniform, kCalibrationCpu, 5);
  EXPECT_DOUBLE_EQ(v.speedup_total.value, before) << "the verdict itself does not carry the calibration";
  EXPECT_LT(v.calibration.speedup_total_if_alone.value, before);
  const auto j = pipeline::verdict_json(v)["calibration"];
  EXPECT_DOUBLE_EQ(j["cpu_seconds_per_scene"].get<double>(), kCalibrationCpu / 5);
}

TEST(PricedVerdict, HeadToHeadChargesEachFamilyItsOwnPredictor) {
  // The same family against itself: 1x when both predictors cost alike; a
  // dearer predictor on the slow side makes the fast side faster in total,
  // never in CFD CPU.
  const Families f = families(0.0, 1);
  const auto even = pipeline::make_verdict(kPrimary, f.clustered, f.clustered, 2.0, 2.0);
  EXPECT_NEAR(even.speedup_total.value, 1.0, 1e-9);
  EXPECT_NEAR(even.speedup_cfd.value, 1.0, 1e-9);
  const auto dear = pipeline::make_verdict(kPrimary, f.clustered, f.clustered, 2.0, 50.0);
  EXPECT_GT(dear.speedup_total.value, 2.0);
  EXPECT_NEAR(dear.speedup_cfd.value, 1.0, 1e-9);
}
