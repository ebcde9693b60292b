// The averaging loop of precision on demand on a small wedge, with a
// measure supplied by the test (the real one, shockfit's, is the pipeline's:
// tests/pipeline/precision_test.cpp): which rule stops the run, chunks that
// reproduce one uninterrupted run, and the summary keys.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "granular/flow_run.hpp"
#include "scene/scene.hpp"

namespace {

// Chunks end at the whole snapshot nearest to each check time: on this
// 40-cell lattice a snapshot is ~1/80 flow-through time, half of it the
// rounding.
constexpr double kFlowThroughTol = 0.01;

const char* kSmallWedge = R"(
name: small_wedge_precision
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {inflow_packing_fraction: 0.05, body_diameters: 40, lattice_nx: 40, lattice_ny: 30, warmup: 0.5, replicas: 2, seed: 5}
)";

// A measure that improves by a known law: half-width 1 / (number of checks).
granular::PrecisionGoal counting_goal(double target, std::shared_ptr<int> calls) {
  granular::PrecisionGoal g;
  g.target = target;
  g.target_source = "test";
  g.measure = [calls](const scene::Lattice&, const std::vector<scene::Lattice>&) {
    granular::PrecisionMeasure m;
    m.half_width = 1.0 / ++*calls;
    m.quantity = "count";
    return m;
  };
  return g;
}

void expect_same_fields(const granular::FlowResult& a, const granular::FlowResult& b) {
  for (const char* name : {"volume_fraction", "u", "v", "temperature", "volume_fraction_se"}) {
    const auto& fa = a.fields.field(name);
    const auto& fb = b.fields.field(name);
    ASSERT_EQ(fa.size(), fb.size());
    for (std::size_t k = 0; k < fa.size(); ++k)
      if (!std::isnan(fa[k]) || !std::isnan(fb[k])) {
        ASSERT_EQ(fa[k], fb[k]) << name << " cell " << k;
      }
  }
}

}  // namespace

TEST(FlowPrecision, StopsWhenTwoChecksInARowMeetTheTarget) {
  // Checks at 1, 1.5, 2, 2.5 flow-through times give 1, 1/2, 1/3, 1/4: a
  // target of 0.4 is met by the third and, the second time in a row, by the
  // fourth.
  const scene::Scene s = scene::parse_scene(kSmallWedge);
  auto calls = std::make_shared<int>(0);
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, counting_goal(0.4, calls));
  const nlohmann::json& j = r.summary;
  EXPECT_EQ(j["stopped_by"], "precision");
  EXPECT_EQ(*calls, 4);
  EXPECT_NEAR(j["averaging_flow_throughs"].get<double>(),
              granular::kFirstCheckFlowThroughs + 3 * granular::kCheckEveryFlowThroughs,
              kFlowThroughTol);
  EXPECT_NEAR(j["precision"]["half_width"].get<double>(), 0.25, 1e-15);
  EXPECT_EQ(j["precision"]["target_half_width"], 0.4);
  ASSERT_EQ(j["precision"]["checks"].size(), 4u);
  EXPECT_GT(j["cpu_seconds"].get<double>(), 0.0);
  EXPECT_TRUE(j["cpu_budget"].is_null());
}

TEST(FlowPrecision, NoStopBeforeTheGoalsMinimum) {
  // Every check meets the target, but the goal asks for at least 2.5
  // flow-through times: checks start one interval earlier (2, 2.5), so the
  // run stops at the minimum itself, not at the second check (1.5).
  const scene::Scene s = scene::parse_scene(kSmallWedge);
  auto calls = std::make_shared<int>(0);
  granular::PrecisionGoal g = counting_goal(10.0, calls);
  g.min_flow_throughs = 2.5;
  g.unit = "deg";
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "precision");
  EXPECT_EQ(*calls, 2);
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), 2.5, kFlowThroughTol);
  EXPECT_EQ(r.summary["precision"]["min_flow_throughs"], 2.5);
  EXPECT_EQ(r.summary["precision"]["target_unit"], "deg");
}

TEST(FlowPrecision, AChangeOfQuantityRestartsTheCount) {
  // Every check meets the target, but the quantity alternates (a shock
  // classified differently from one chunk to the next): never two in a row
  // of one kind, so the run goes on to max_averaging.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 2.0;
  auto calls = std::make_shared<int>(0);
  granular::PrecisionGoal g;
  g.target = 1.0;
  g.measure = [calls](const scene::Lattice&, const std::vector<scene::Lattice>&) {
    granular::PrecisionMeasure m;
    m.half_width = 0.1;
    m.quantity = ++*calls % 2 ? "standoff" : "shock_angle";
    return m;
  };
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "averaging");
  EXPECT_EQ(*calls, 3);
}

TEST(FlowPrecision, AShockStillMovingIsNotPrecise) {
  // Every check meets the target, but the shock moves by twice the target
  // between checks (a flow still settling): never "precision"; once it
  // stands still (from the fourth check on), two checks in a row stop it.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 4.0;
  auto calls = std::make_shared<int>(0);
  granular::PrecisionGoal g;
  g.target = 0.01;
  g.measure = [calls](const scene::Lattice&, const std::vector<scene::Lattice>&) {
    granular::PrecisionMeasure m;
    m.half_width = 0.005;
    m.quantity = "shock_angle";
    m.value = std::min(++*calls, 3) * 0.02;  // body lengths per unit: 1
    m.value_to_position = 1.0;
    return m;
  };
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "precision");
  EXPECT_EQ(*calls, 4);
  ASSERT_EQ(r.summary["precision"]["checks"].size(), 4u);
  EXPECT_EQ(r.summary["precision"]["checks"][3]["value"], 0.06);
}

TEST(FlowPrecision, StopsWhenTheIntervalNoLongerShrinks) {
  // An interval that stays put: an impossible target is not averaged to
  // max_averaging; the run stops at the second check that doubled its time
  // without narrowing (2.5 flow-through times, checks at 1, 1.5, 2, 2.5).
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 8.0;
  granular::PrecisionGoal g;
  g.target = 1e-9;
  g.measure = [](const scene::Lattice&, const std::vector<scene::Lattice>&) {
    granular::PrecisionMeasure m;
    m.half_width = 0.05;
    m.quantity = "shock_angle";
    return m;
  };
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "plateau");
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), 2.5, kFlowThroughTol);
}

TEST(FlowPrecision, StopsWhenAveragingNoLongerPays) {
  // Later stages that do not care how wide the interval is: from the goal's
  // minimum on, the second check in a row at which the next chunk saves them
  // nothing stops the run (checks at 1.5 and 2 for a minimum of 2), though
  // the interval still shrinks and the target is far.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 8.0;
  auto calls = std::make_shared<int>(0);
  granular::PrecisionGoal g = counting_goal(1e-9, calls);
  g.min_flow_throughs = 2.0;
  g.downstream_cpu = [](double, double) { return 100.0; };
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "cost");
  EXPECT_EQ(*calls, 2);
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), 2.0, kFlowThroughTol);
  const nlohmann::json& checks = r.summary["precision"]["checks"];
  ASSERT_EQ(checks.size(), 2u);
  for (const auto& c : checks) {
    EXPECT_EQ(c["expected_saving_cpu_seconds"], 0.0);
    EXPECT_GT(c["next_chunk_cpu_seconds"].get<double>(), 0.0);
  }
}

TEST(FlowPrecision, AveragingThatPaysGoesOnToTheCap) {
  // Later stages that pay far more for width than any chunk costs: no cost
  // stop; an interval shrinking as 1/checks neither plateaus nor meets the
  // target, so the cap stops it. The last chunk has no next one to price.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 2.5;
  auto calls = std::make_shared<int>(0);
  granular::PrecisionGoal g = counting_goal(1e-9, calls);
  g.downstream_cpu = [](double, double hw) { return 1e9 * hw; };
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, g);
  EXPECT_EQ(r.summary["stopped_by"], "averaging");
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), 2.5, kFlowThroughTol);
  const nlohmann::json& checks = r.summary["precision"]["checks"];
  ASSERT_EQ(checks.size(), 4u);
  for (std::size_t k = 0; k + 1 < checks.size(); ++k)
    EXPECT_GT(checks[k]["expected_saving_cpu_seconds"].get<double>(),
              checks[k]["next_chunk_cpu_seconds"].get<double>());
  EXPECT_FALSE(checks[3].contains("expected_saving_cpu_seconds"));
}

TEST(FlowPrecision, StopsAtTheBudgetOnAnImpossibleTarget) {
  // The first chunk always runs; a budget already spent then stops it.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.cpu_budget = 1e-3;
  auto calls = std::make_shared<int>(0);
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, counting_goal(1e-9, calls));
  EXPECT_EQ(r.summary["stopped_by"], "budget");
  EXPECT_EQ(*calls, 1);
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), granular::kFirstCheckFlowThroughs,
              kFlowThroughTol);
  EXPECT_EQ(r.summary["cpu_budget"], 1e-3);
}

TEST(FlowPrecision, ChunksReproduceOneUninterruptedRun) {
  // An impossible target and no budget: the run averages max_averaging in
  // chunks (checks at 1 and 1.5) and stops by "averaging" with the fields,
  // bit for bit, of a fixed run of the same length, and again on a rerun.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.max_averaging = 1.5;
  auto calls = std::make_shared<int>(0);
  granular::RunOptions o;
  o.np = 2;
  const granular::FlowResult chunked =
      granular::run_flow_scene(s, o, {}, counting_goal(1e-9, calls));
  EXPECT_EQ(chunked.summary["stopped_by"], "averaging");
  EXPECT_EQ(*calls, 2);
  const granular::FlowResult again = granular::run_flow_scene(s, o, {}, counting_goal(1e-9, calls));
  expect_same_fields(chunked, again);

  s.granular.averaging = chunked.summary["averaging_flow_throughs"].get<double>();
  const granular::FlowResult fixed = granular::run_flow_scene(s, o);
  EXPECT_EQ(fixed.summary["stopped_by"], "averaging");
  EXPECT_TRUE(fixed.summary["precision"].is_null());
  expect_same_fields(chunked, fixed);
  EXPECT_EQ(chunked.summary["collisions"], fixed.summary["collisions"]);
}

TEST(FlowPrecision, SingleReplicaChunksKeepBatchesForTheSpread) {
  // One replica: every chunk is cut into batches, regrouped into the same
  // number of consecutive batches, so the per-cell spread still exists.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.replicas = 1;
  s.granular.max_averaging = 1.5;
  auto calls = std::make_shared<int>(0);
  const granular::FlowResult r = granular::run_flow_scene(s, {}, {}, counting_goal(1e-9, calls));
  EXPECT_EQ(r.summary["stopped_by"], "averaging");
  int finite = 0;
  for (const double x : r.fields.field("volume_fraction_se"))
    finite += std::isfinite(x) && x > 0.0 ? 1 : 0;
  EXPECT_GT(finite, 0);
}

TEST(FlowPrecision, BudgetAloneStopsAFixedAveraging) {
  // No target: granular.averaging, cut short by the budget.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.averaging = 3.0;
  s.granular.cpu_budget = 1e-3;
  const granular::FlowResult r = granular::run_flow_scene(s, granular::RunOptions{});
  EXPECT_EQ(r.summary["stopped_by"], "budget");
  EXPECT_NEAR(r.summary["averaging_flow_throughs"].get<double>(), granular::kCheckEveryFlowThroughs,
              kFlowThroughTol);
  EXPECT_TRUE(r.summary["precision"].is_null());
}
