// The granular stream's steady-state rule on synthetic disk counts; no
// engine run needed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "steady_state.hpp"

namespace {

// Samples every 0.1 time units, a check every 4 samples, windows of 10
// samples, no check before time 2 (the 20th sample).
constexpr double kSampleDt = 0.1;
constexpr std::size_t kCheckEvery = 4;
constexpr std::size_t kWindow = 10;
constexpr double kMinTime = 2.0;
// Disks in the domain once steady.
constexpr double kCount = 1000.0;

granular::FlowSteadyCriteria criteria() {
  granular::FlowSteadyCriteria c;
  c.window = kWindow;
  c.check_every = kCheckEvery;
  c.min_time = kMinTime;
  return c;
}

// Feeds samples k = 1..n; returns the 1-based sample at which the rule
// declared steady, or 0 if never.
int steady_at(granular::FlowSteadyState& rule, int n, const std::function<double(int)>& count) {
  for (int k = 1; k <= n; ++k) {
    (void)rule.add(k * kSampleDt, count(k));
    if (rule.steady()) return k;
  }
  return 0;
}

TEST(FlowSteadyState, FlatCountIsSteadyAtTheFirstCheckAfterMinTime) {
  granular::FlowSteadyState rule(criteria());
  // Sample 20 is at time 2.0 and a check (20 % 4 == 0) with 2 windows.
  EXPECT_EQ(steady_at(rule, 100, [](int) { return kCount; }), 20);
  EXPECT_NE(rule.why().find("steady"), std::string::npos) << rule.why();
}

TEST(FlowSteadyState, FillingDomainIsNotSteadyUntilTheCountSettles) {
  // The prefilled domain drains towards kCount with a time constant of 10
  // samples: the window means differ by less than 2% from about sample 50.
  granular::FlowSteadyState rule(criteria());
  const int at = steady_at(rule, 200, [](int k) { return kCount * (1.0 + std::exp(-k / 10.0)); });
  EXPECT_GT(at, 40);
  EXPECT_LT(at, 70);
  EXPECT_EQ(at % static_cast<int>(kCheckEvery), 0);
}

TEST(FlowSteadyState, RisingCountIsNeverSteady) {
  // A stagnation zone that keeps growing: +1% per sample.
  granular::FlowSteadyState rule(criteria());
  EXPECT_EQ(steady_at(rule, 200, [](int k) { return kCount * (1.0 + 0.01 * k); }), 0);
  EXPECT_NE(rule.why().find("drifting"), std::string::npos) << rule.why();
}

TEST(FlowSteadyState, SmallNoisySystemIsSteadyWithinItsCountingNoise) {
  // 20 disks +-1: window means differ by far more than 2% of 20 but stay
  // within two standard errors of the count (2 sqrt(20 / 10) = 2.8).
  granular::FlowSteadyState rule(criteria());
  EXPECT_EQ(steady_at(rule, 100, [](int k) { return 20.0 + ((k / 10) % 2 ? 1.0 : -1.0); }), 20);
}

TEST(FlowSteadyState, TooEarlyIsNeverCheckedOrSteady) {
  granular::FlowSteadyState rule(criteria());
  for (int k = 1; k < 20; ++k) {
    EXPECT_FALSE(rule.add(k * kSampleDt, kCount));
    EXPECT_FALSE(rule.steady());
  }
  EXPECT_NE(rule.why().find("too early"), std::string::npos) << rule.why();
  EXPECT_TRUE(rule.add(20 * kSampleDt, kCount));
}

TEST(FlowSteadyState, OnlyEveryCheckEverySampleIsChecked) {
  granular::FlowSteadyCriteria c = criteria();
  c.min_time = 0.0;
  c.window = 100;  // never enough samples: checks report "too few"
  granular::FlowSteadyState rule(c);
  for (int k = 1; k <= 12; ++k)
    EXPECT_EQ(rule.add(k * kSampleDt, kCount), k % static_cast<int>(kCheckEvery) == 0) << k;
  EXPECT_NE(rule.why().find("too few"), std::string::npos) << rule.why();
}

TEST(FlowSteadyState, WindowTestMatchesTheReplicaHelper) {
  // counts_steady (flow_replica.hpp) is the same window test with the
  // default tolerances.
  std::vector<double> flat(40, kCount);
  EXPECT_TRUE(granular::counts_settled(flat, kWindow, criteria().rel_tol, criteria().noise_sigmas));
  flat.back() = 2 * kCount;
  EXPECT_FALSE(
      granular::counts_settled(flat, kWindow, criteria().rel_tol, criteria().noise_sigmas));
}

}  // namespace
