// The steady-state rule on synthetic histories; no OpenFOAM needed.
#include "steady_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace {

// Written times every 0.2 flow-throughs (the scene default), so min_time 1
// is reached at the 5th row.
constexpr double kRowFlowThroughs = 0.2;
// Steps per row of the synthetic histories, and steps per flow-through under
// the iterations clock (LTS).
constexpr long kRowSteps = 60;
constexpr long kStepsPerFlowThrough = 300;
// Body force magnitude of the synthetic histories.
constexpr double kForce = 2.0;

scene::CfdParams defaults() {
  return scene::CfdParams{};
}

struct Sample {
  double drho = 0, dforce = 0, force = kForce;
};

// Rows k = 1..n with the sample for each row, the time-accurate clock's
// flow-throughs and the steps filled in.
std::vector<cfd::HistoryRow> history(int n, const std::function<Sample(int)>& at) {
  std::vector<cfd::HistoryRow> rows;
  for (int k = 1; k <= n; ++k) {
    const Sample s = at(k);
    cfd::HistoryRow r;
    r.flow_throughs = k * kRowFlowThroughs;
    r.time = r.flow_throughs;
    r.steps = k * kRowSteps;
    r.drho_l2 = s.drho;
    r.dforce = s.dforce;
    r.force = {0.0, s.force};
    rows.push_back(r);
  }
  return rows;
}

// Feeds rows one by one; returns the 1-based row at which the rule first
// declared steady, or 0 if never.
int steady_at(cfd::SteadyState& rule, const std::vector<cfd::HistoryRow>& rows) {
  for (std::size_t k = 0; k < rows.size(); ++k) {
    rule.add(rows[k]);
    if (rule.steady()) return static_cast<int>(k + 1);
  }
  return 0;
}

TEST(SteadyState, DecayingHistoryIsSteadyOnceBelowBothTolerancesTwice) {
  // Both halve every row: drho from 1 is below 0.05 from row 6 (0.031), dF
  // from 0.1 below 2e-3 from row 7 (1.6e-3); the second pass is row 8.
  const auto rows = history(20, [](int k) {
    return Sample{std::pow(0.5, k - 1), 0.1 * std::pow(0.5, k - 1)};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(rule, rows), 8);
  EXPECT_NE(rule.why().find("steady"), std::string::npos) << rule.why();
}

TEST(SteadyState, TooEarlyIsNeverSteady) {
  // Quiet from the first row, but min_time (1 flow-through) is only reached
  // at row 5; the two checks then pass at rows 5 and 6.
  const auto rows = history(6, [](int) { return Sample{1e-4, 1e-5}; });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  for (int k = 0; k < 4; ++k) {
    rule.add(rows[static_cast<std::size_t>(k)]);
    EXPECT_FALSE(rule.steady());
    EXPECT_NE(rule.why().find("too early"), std::string::npos) << rule.why();
  }
  rule.add(rows[4]);
  EXPECT_FALSE(rule.steady());
  rule.add(rows[5]);
  EXPECT_TRUE(rule.steady());
}

TEST(SteadyState, NoisyPlateauAboveTheToleranceIsSteadyAtTheNoiseFloor) {
  // A captured shock's flicker: drho stalls at 0.1 (twice steady_tol) with
  // +-10% noise while the body force is still to 1e-4.
  const auto rows = history(30, [](int k) {
    const double noise = (k % 2 == 0 ? 0.1 : -0.1);
    return Sample{0.1 * (1.0 + noise), 5e-3, kForce * (1.0 + 1e-4 * noise)};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  // The plateau needs two windows of 5 rows: first at row 10, twice at 11.
  EXPECT_EQ(steady_at(rule, rows), 11);
  EXPECT_NE(rule.why().find("noise floor"), std::string::npos) << rule.why();
}

TEST(SteadyState, StillFallingPlateauIsNotSteady) {
  // Above the tolerance and falling 10% per row: each window of 5 rows is
  // 0.9^5 = 0.59 times the one before, below kStillFalling.
  const auto rows = history(30, [](int k) { return Sample{10.0 * std::pow(0.9, k), 5e-3}; });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  // 10 * 0.9^k < 0.05 from k = 51 on: never within 30 rows.
  EXPECT_EQ(steady_at(rule, rows), 0);
  EXPECT_NE(rule.why().find("changing"), std::string::npos) << rule.why();
}

TEST(SteadyState, OscillatingForceIsNotSteady) {
  // The density change has stalled (noise floor) but the body force swings
  // by 2% (ten times force_tol): a shedding or buzzing flow, not steady.
  const auto rows = history(40, [](int k) {
    return Sample{0.1, 0.05, kForce * (1.0 + 0.01 * std::sin(k))};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(rule, rows), 0);
}

TEST(SteadyState, OneBadRowResetsTheCount) {
  // Quiet after min_time except for one spike at row 6.
  const auto rows = history(10, [](int k) {
    return k == 6 ? Sample{1.0, 1.0} : Sample{1e-3, 1e-4};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(rule, rows), 8);
}

TEST(SteadyState, SteadyStaysSteady) {
  auto rows = history(8, [](int) { return Sample{1e-3, 1e-4}; });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  ASSERT_EQ(steady_at(rule, rows), 6);
  const std::string why = rule.why();
  cfd::HistoryRow spike = rows.back();
  spike.drho_l2 = 1.0;
  rule.add(spike);
  EXPECT_TRUE(rule.steady());
  EXPECT_EQ(rule.why(), why);
}

TEST(SteadyState, IterationClockCountsStepsNotPseudoTime) {
  // Under LTS the pseudo-time of a row says nothing: a clustered grid's rows
  // are 1e-3 "flow-throughs" of pseudo-time apart. With 300 steps per
  // flow-through and 60 steps per row, min_time is reached at row 5.
  auto rows = history(8, [](int) { return Sample{1e-3, 1e-4}; });
  for (auto& r : rows) r.flow_throughs *= 1e-3;
  cfd::SteadyState ta(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(ta, rows), 0);
  EXPECT_NE(ta.why().find("too early"), std::string::npos) << ta.why();
  cfd::SteadyState lts(cfd::SteadyCriteria::iteration_windows(defaults(), kStepsPerFlowThrough));
  EXPECT_EQ(steady_at(lts, rows), 6);
  EXPECT_DOUBLE_EQ(lts.progress(rows[4]), 1.0);
}

TEST(SteadyState, IterationClockTooEarlyCountsIterations) {
  const auto rows = history(1, [](int) { return Sample{1e-3, 1e-4}; });
  cfd::SteadyState lts(cfd::SteadyCriteria::iteration_windows(defaults(), kStepsPerFlowThrough));
  lts.add(rows[0]);
  EXPECT_NE(lts.why().find("iteration flow-throughs"), std::string::npos) << lts.why();
}

TEST(SteadyState, CriteriaFollowTheScene) {
  scene::CfdParams p;
  p.steady_tol = 0.1;
  p.force_tol = 1e-2;
  p.min_time = 2.0;
  p.steady_checks = 3;
  const auto c = cfd::SteadyCriteria::iteration_windows(p, 0);
  EXPECT_EQ(c.steady_tol, 0.1);
  EXPECT_EQ(c.force_tol, 1e-2);
  EXPECT_EQ(c.min_time, 2.0);
  EXPECT_EQ(c.steady_checks, 3);
  EXPECT_EQ(c.steps_per_flow_through, 1);  // never a division by zero
}

}  // namespace
