// The crossing of the granular angle with the gas angle over a sweep of e,
// and the next e to run (cases seen in the calibration sweeps).
#include "pipeline/restitution_crossing.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/units.hpp"

namespace {
using pipeline::SweepPoint;
using scene::kNaN;
constexpr double kTolerance = 1e-12;
}  // namespace

TEST(RestitutionCrossing, InterpolatesBetweenNeighbours) {
  const std::vector<SweepPoint> pts{{0.96, 27.25, 1.0}, {0.98, 32.28, 1.0}, {1.0, 48.68, 0.26}};
  const auto c = pipeline::find_crossing(pts, 35.87);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->e, 0.98 + 0.02 * (35.87 - 32.28) / (48.68 - 32.28), kTolerance);
  EXPECT_NEAR(c->e_ci, 0.5 * 1.26 * 0.02 / (48.68 - 32.28), kTolerance);
  EXPECT_EQ(c->e_low, 0.98);
  EXPECT_EQ(c->e_high, 1.0);
  EXPECT_NEAR(*pipeline::next_restitution(pts, 35.87), 0.99, kTolerance);
}

TEST(RestitutionCrossing, AMisfitInsideTheBracketIsSkipped) {
  // M2.5/8: the run at e = 0.99 was classed detached (no angle); the
  // crossing lies between its usable neighbours, and 0.99 is not rerun.
  const std::vector<SweepPoint> pts{
      {0.96, 19.23, 0.71}, {0.98, 25.84, 0.76}, {0.99, kNaN, kNaN}, {1.0, 34.79, 0.43}};
  const auto c = pipeline::find_crossing(pts, 30.01);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->e_low, 0.98);
  EXPECT_EQ(c->e_high, 1.0);
  EXPECT_FALSE(pipeline::next_restitution(pts, 30.01).has_value());
}

TEST(RestitutionCrossing, SearchesTowardsTheGasAngleWithoutACrossing) {
  // M2.5/20: e = 1 too noisy to use (ci 6 deg), everything usable below
  // the gas angle: halfway up to the unusable run.
  const std::vector<SweepPoint> up{{0.96, 32.16, 1.45}, {0.98, 38.25, 1.01}, {1.0, 58.57, 6.03}};
  EXPECT_FALSE(pipeline::find_crossing(up, 42.89).has_value());
  EXPECT_NEAR(*pipeline::next_restitution(up, 42.89), 0.99, kTolerance);
  // M4.5/8: e = 0.96 misfit, the usable runs above the gas angle: halfway down.
  const std::vector<SweepPoint> down{{0.96, kNaN, kNaN}, {0.98, 19.34, 0.42}, {1.0, 23.35, 0.15}};
  EXPECT_NEAR(*pipeline::next_restitution(down, 18.84), 0.97, kTolerance);
  // Nothing below: one sweep step down.
  const std::vector<SweepPoint> step{{0.98, 19.34, 0.42}, {1.0, 23.35, 0.15}};
  EXPECT_NEAR(*pipeline::next_restitution(step, 18.84), 0.96, kTolerance);
  // Below the gas angle even at e = 1: no e <= 1 can reach it.
  const std::vector<SweepPoint> top{{0.98, 19.0, 0.4}, {1.0, 20.0, 0.2}};
  EXPECT_FALSE(pipeline::next_restitution(top, 25.0).has_value());
}

// A blunt body's sweep: standoff ratios on the line 1 + 20 (e - 0.965), one
// run in the bracket off by twice its interval. The bracket's interpolation
// follows the stray run; the line through the five runs stays near 0.965
// and its interval covers it.
TEST(RestitutionCrossing, ALineThroughSeveralRunsOutvotesAStrayOne) {
  const auto ratio = [](double e) { return 1.0 + 20.0 * (e - 0.965); };
  std::vector<SweepPoint> pts;
  for (const double e : {0.955, 0.96, 0.9625, 0.97, 0.975}) pts.push_back({e, ratio(e), 0.02});
  pts[2].angle += 0.04;  // e = 0.9625 reads 2 intervals high
  const auto bracket = pipeline::find_crossing(pts, 1.0);
  const auto line = pipeline::find_crossing_by_line(pts, 1.0, 0.012);
  ASSERT_TRUE(bracket && line);
  EXPECT_GT(std::abs(bracket->e - 0.965), 0.0015);
  EXPECT_LT(std::abs(line->e - 0.965), 0.0005);
  EXPECT_LT(std::abs(line->e - 0.965), line->e_ci);
  EXPECT_EQ(line->e_low, bracket->e_low);

  // Exact runs: the line is the truth, its interval the runs' alone.
  pts[2].angle = ratio(0.9625);
  const auto exact = pipeline::find_crossing_by_line(pts, 1.0, 0.012);
  ASSERT_TRUE(exact);
  EXPECT_NEAR(exact->e, 0.965, kTolerance);
  EXPECT_LT(exact->e_ci, 0.001);

  // Fewer than three runs near the crossing: the bracket's answer.
  const std::vector<SweepPoint> two{{0.96, ratio(0.96), 0.02}, {0.97, ratio(0.97), 0.02}};
  EXPECT_NEAR(pipeline::find_crossing_by_line(two, 1.0, 0.0075)->e,
              pipeline::find_crossing(two, 1.0)->e, kTolerance);
}

// A wedge's sweep near its crossing: angle(e) convex, as measured
// (M4.5/14: 24.1, 25.2, 26.5 deg at 0.97, 0.975, 0.98). A chord across the
// bracket reads the crossing low; the parabola through the runs near it
// recovers it, with an interval from the runs' own.
TEST(RestitutionCrossing, AParabolaFollowsTheConvexAngleThatAChordCuts) {
  const double e0 = 0.9732, target = 24.48;
  const auto angle = [&](double e) {
    const double x = e - e0;
    return target + 250.0 * x + 16000.0 * x * x;
  };
  std::vector<SweepPoint> pts;
  for (const double e : {0.96, 0.965, 0.97, 0.975, 0.98, 1.0}) pts.push_back({e, angle(e), 0.2});
  const auto chord = pipeline::find_crossing(pts, target);
  const auto curve = pipeline::find_crossing_by_curve(pts, target, 0.0105);
  ASSERT_TRUE(chord && curve);
  EXPECT_LT(chord->e, e0 - 1e-4);  // the chord's bias, about 0.1 deg of angle
  EXPECT_NEAR(curve->e, e0, 1e-9);
  EXPECT_GT(curve->e_ci, 0.0);
  EXPECT_LT(curve->e_ci, 0.002);
  EXPECT_EQ(curve->e_low, chord->e_low);
  EXPECT_EQ(curve->e_high, chord->e_high);

  // Noisy runs (+-1 sd, alternating): the crossing stays within its interval.
  auto noisy = pts;
  for (std::size_t i = 0; i < noisy.size(); ++i) noisy[i].angle += (i % 2 ? 0.1 : -0.1);
  const auto n = pipeline::find_crossing_by_curve(noisy, target, 0.0105);
  ASSERT_TRUE(n);
  EXPECT_LT(std::abs(n->e - e0), n->e_ci);
}

TEST(RestitutionCrossing, TheParabolaGivesWayToTheLineWhereItCannotServe) {
  const auto line = [](double e) { return 20.0 + 300.0 * (e - 0.97); };
  // Two runs in the window: the bracket's interpolation.
  const std::vector<SweepPoint> two{{0.96, line(0.96), 0.2}, {0.98, line(0.98), 0.2}};
  EXPECT_NEAR(pipeline::find_crossing_by_curve(two, 20.0, 0.0105)->e,
              pipeline::find_crossing(two, 20.0)->e, kTolerance);
  // Outer runs that bend the parabola over between the bracketing runs
  // (its vertex at 0.9725): the line through the same runs instead.
  const std::vector<SweepPoint> bent{
      {0.965, 22.0, 0.2}, {0.97, 19.9, 0.2}, {0.975, 20.1, 0.2}, {0.98, 22.0, 0.2}};
  EXPECT_NEAR(pipeline::find_crossing_by_curve(bent, 20.0, 0.0105)->e,
              pipeline::find_crossing_by_line(bent, 20.0, 0.0105)->e, kTolerance);
}

TEST(RestitutionCrossing, TheMeanOfSeedsWeighsTheRunsByTheirIntervals) {
  const auto m = pipeline::mean_point(0.97, {{0.97, 20.0, 0.2}, {0.97, 21.0, 0.4}});
  EXPECT_NEAR(m.angle, (20.0 / 0.04 + 21.0 / 0.16) / (1 / 0.04 + 1 / 0.16), kTolerance);
  EXPECT_NEAR(m.ci, 1.0 / std::sqrt(1 / 0.04 + 1 / 0.16), kTolerance);
  // A misfit (no angle, or an interval too wide to use) does not count.
  const auto u = pipeline::mean_point(0.97, {{0.97, 20.0, 0.2}, {0.97, kNaN, kNaN}, {0.97, 5, 40}});
  EXPECT_NEAR(u.angle, 20.0, kTolerance);
  EXPECT_TRUE(std::isnan(pipeline::mean_point(0.97, {{0.97, kNaN, kNaN}}).angle));
}

TEST(RestitutionCrossing, AStepOfTheAngleIsFlaggedAndAConvexRiseIsNot) {
  // M9/24.5 swept at 12 flow-through times: 4.2 deg between e = 0.94 and
  // 0.95, flat above; the gas angle (31.67) is met only at the step's foot.
  const std::vector<SweepPoint> step = {{0.92, 27.13, 0.16},
                                        {0.94, 27.88, 0.27},
                                        {0.95, 32.07, 0.61},
                                        {0.96, 32.04, 0.33},
                                        {0.98, 36.22, 0.16}};
  EXPECT_TRUE(pipeline::crossing_on_step(step, 31.67));
  // The same runs with intervals wider than the step: noise, not a step.
  std::vector<SweepPoint> noisy = step;
  for (auto& p : noisy) p.ci = 4.0;
  EXPECT_FALSE(pipeline::crossing_on_step(noisy, 31.67));
  // Near Mach 2 angle(e) climbs steeply towards e = 1, but convex: each
  // segment steeper than the one below (M2/8: 33.7, 37.1, 43.2 deg at
  // 0.99, 0.995, 1; gas 37.2; the crossing's bracket is the top one).
  const std::vector<SweepPoint> convex = {
      {0.98, 30.9, 0.5}, {0.99, 33.7, 0.6}, {0.995, 37.1, 0.7}, {1.0, 43.2, 0.8}};
  EXPECT_FALSE(pipeline::crossing_on_step(convex, 37.2));
  EXPECT_FALSE(pipeline::crossing_on_step(convex, 34.0));  // below the top bracket: convex too
  // No crossing: nothing to flag.
  EXPECT_FALSE(pipeline::crossing_on_step(step, 40.0));
}
