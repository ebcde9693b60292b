// The steady-state rule on synthetic histories; no OpenFOAM needed.
#include "steady_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"

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

// A row's measures. Without an explicit force, the force moves as dforce
// says: it grows by dforce x kForce per flow-through, so the force's trend
// over a window and the row-to-row change tell the same story.
struct Sample {
  double drho = 0, dforce = 0, force = std::numeric_limits<double>::quiet_NaN();
};

// Rows k = 1..n with the sample for each row, the time-accurate clock's
// flow-throughs and the steps filled in.
std::vector<cfd::HistoryRow> history(int n, const std::function<Sample(int)>& at) {
  std::vector<cfd::HistoryRow> rows;
  double moved = 0;  // force change so far, relative, when the sample sets none
  for (int k = 1; k <= n; ++k) {
    const Sample s = at(k);
    cfd::HistoryRow r;
    r.flow_throughs = k * kRowFlowThroughs;
    r.time = r.flow_throughs;
    r.steps = k * kRowSteps;
    r.drho_l2 = s.drho;
    r.dforce = s.dforce;
    moved += s.dforce * kRowFlowThroughs;
    r.force = {0.0, std::isnan(s.force) ? kForce * (1.0 + moved) : s.force};
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
  // The plateau needs one window of 5 rows and min_time: first at row 5,
  // twice at 6 (the former rule compared two windows: row 11).
  EXPECT_EQ(steady_at(rule, rows), 6);
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

// The relative change of an alternating force between two rows, per
// flow-through: 2 a / kRowFlowThroughs.
double alternating_dforce(double a) {
  return 2.0 * a / kRowFlowThroughs;
}

TEST(SteadyState, FlickeringForceIsSettledByItsTrendNotItsRowToRowChange) {
  // A converged captured shock: the density change below steady_tol, the
  // force flickering by +-0.12% about a fixed mean (the recorded wedges:
  // 0.05-0.2%). Row to row that is 1.2% per flow-through, six times
  // force_tol, and the window's range (0.24%) exceeds force_tol too, so the
  // row-to-row rule never passes; the window's trend is zero and its scatter
  // (0.15%) within force_tol: steady once min_time is reached and the window
  // full (row 5), twice at row 6.
  constexpr double a = 1.2e-3;
  const auto rows = history(20, [](int k) {
    return Sample{0.04, alternating_dforce(a), kForce * (1.0 + (k % 2 == 0 ? a : -a))};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(rule, rows), 6);
  EXPECT_NE(rule.why().find("force trend"), std::string::npos) << rule.why();
}

TEST(SteadyState, DriftingForceUnderFlickerIsNotSteady) {
  // The same flicker on a force still growing by 0.5% per flow-through
  // (2.5 force_tol): the trend sees the drift through the flicker.
  constexpr double a = 1.2e-3, drift = 5e-3;
  const auto rows = history(30, [](int k) {
    const double t = k * kRowFlowThroughs;
    return Sample{0.04, alternating_dforce(a), kForce * (1.0 + drift * t + (k % 2 == 0 ? a : -a))};
  });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(rule, rows), 0);
  EXPECT_NE(rule.why().find("force trend 0.00"), std::string::npos) << rule.why();
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

TEST(SteadyState, IterationClockTakesAPlateauOnlyNearTheNoiseFloor) {
  // A clustered grid under LTS: the coarse cells settle first and the
  // density change stalls at 0.45 (9x steady_tol) with a still body force
  // while the fine band is still converging; then it falls to its floor.
  const auto rows = history(30, [](int k) {
    const double noise = (k % 2 == 0 ? 0.05 : -0.05);
    const double drho = k <= 14 ? 0.45 : 0.07;
    return Sample{drho * (1.0 + noise), 5e-3, kForce * (1.0 + 1e-4 * noise)};
  });
  cfd::SteadyState ta(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(ta, rows), 6);  // time-accurately any plateau counts
  cfd::SteadyState lts(cfd::SteadyCriteria::iteration_windows(defaults(), kStepsPerFlowThrough));
  // Under LTS the false plateau does not count; the floor at 0.07 does,
  // once a whole window of rows sits on it (rows 15-19) and twice.
  EXPECT_EQ(steady_at(lts, rows), 20);
  EXPECT_NE(lts.why().find("noise floor"), std::string::npos) << lts.why();
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

// The bow-shock drift gate. A disc of radius 0.5 at Mach 4, centred at the
// origin: its nose at x = -0.5, the shock at kShockX stands 0.3 off, so the
// gate's tolerance is 0.002 x 0.3 = 0.0006 per flow-through.
constexpr double kDiscRadius = 0.5;
constexpr double kNoseX = -kDiscRadius;
// A cell at the shock (0.02 radii: the standoff is 30 cells, as on the disc
// references) and the shock's position on the stagnation line.
constexpr double kCell = 0.01;
constexpr double kShockX = -0.8;
constexpr double kDriftTol = cfd::kShockDriftPerStandoff * (kNoseX - kShockX);

scene::Scene disc_scene() {
  return scene::parse_scene("name: d\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
}

cfd::SteadyCriteria blunt_criteria() {
  return cfd::SteadyCriteria::time_accurate(defaults()).for_body(disc_scene());
}

// The noise-floor plateau of NoisyPlateauAboveTheToleranceIsSteadyAtTheNoiseFloor
// (steady at row 6 without the gate), its shock on the stagnation line at
// shock(k) for row k.
std::vector<cfd::HistoryRow> plateau_with_shock(int n, const std::function<double(int)>& shock) {
  auto rows = history(n, [](int k) {
    const double noise = (k % 2 == 0 ? 0.1 : -0.1);
    return Sample{0.1 * (1.0 + noise), 5e-3, kForce * (1.0 + 1e-4 * noise)};
  });
  for (int k = 1; k <= n; ++k) {
    rows[static_cast<std::size_t>(k - 1)].shock_x = shock(k);
    rows[static_cast<std::size_t>(k - 1)].shock_cell = kCell;
  }
  return rows;
}

TEST(ShockDriftGate, OnForBodiesWhoseShockMayStandOffOnly) {
  const auto base = cfd::SteadyCriteria::time_accurate(defaults());
  const auto disc = base.for_body(disc_scene());
  EXPECT_DOUBLE_EQ(disc.shock_drift_tol, cfd::kShockDriftPerStandoff);
  EXPECT_DOUBLE_EQ(disc.shock_nose_x, kNoseX);
  // A bow shock's density change must get under the tighter of the two.
  EXPECT_DOUBLE_EQ(disc.steady_tol, cfd::kBowShockSteadyTol);
  scene::CfdParams tight = defaults();
  tight.steady_tol = 1e-3;
  EXPECT_DOUBLE_EQ(cfd::SteadyCriteria::time_accurate(tight).for_body(disc_scene()).steady_tol,
                   1e-3);
  // An attached wedge (M3, 10 deg) is judged as before: no gate, its tolerance.
  const scene::Scene attached = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n");
  EXPECT_EQ(base.for_body(attached).shock_drift_tol, 0.0);
  EXPECT_EQ(base.for_body(attached).steady_tol, base.steady_tol);
  // Beyond the maximum deflection (23 deg at Mach 2) the wedge's shock stands
  // off its apex (the nose, x = 0).
  const scene::Scene detached = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 30, length: 2}\nfreestream: {mach: 2}\n");
  const auto wedge = base.for_body(detached);
  EXPECT_DOUBLE_EQ(wedge.shock_drift_tol, cfd::kShockDriftPerStandoff);
  EXPECT_DOUBLE_EQ(wedge.shock_nose_x, 0.0);
}

TEST(ShockDriftGate, TheToleranceIsTheStandoffsNotTheBodys) {
  // A shock approaching the body by 1% of its standoff per flow-through, as
  // every disc reference did where the body-length gate (0.01 radii per
  // flow-through here, three times this drift) let it stop: not steady.
  const double standoff = kNoseX - kShockX;
  const auto rows = plateau_with_shock(
      40, [&](int k) { return kShockX + 0.01 * standoff * k * kRowFlowThroughs; });
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), 0);
  EXPECT_NE(rule.why().find("of the standoff"), std::string::npos) << rule.why();
}

TEST(ShockDriftGate, AStandoffOfAFewCellsIsHeldToAFractionOfItsCell) {
  // The same standoff on cells ten times coarser (3 cells): 0.2% of it per
  // flow-through is 0.006 of a cell, below what the grid resolves; a drift of
  // 0.015 cells per flow-through (0.5% of the standoff) is steady there, and
  // not on the 30-cell grid.
  const double drift = 0.015 * 10.0 * kCell;
  auto coarse =
      plateau_with_shock(30, [&](int k) { return kShockX + drift * k * kRowFlowThroughs; });
  for (auto& r : coarse) r.shock_cell = 10.0 * kCell;
  cfd::SteadyState coarse_rule(blunt_criteria());
  EXPECT_EQ(steady_at(coarse_rule, coarse), 11);
  const auto fine =
      plateau_with_shock(30, [&](int k) { return kShockX + drift * k * kRowFlowThroughs; });
  cfd::SteadyState fine_rule(blunt_criteria());
  EXPECT_EQ(steady_at(fine_rule, fine), 0);
}

TEST(ShockDriftGate, ABowShockPausedAboveItsDensityToleranceIsNotSteady) {
  // The disc at Mach 5.5: its shock paused for a flow-through with the
  // density change at 0.03-0.045 per flow-through and falling, below the
  // attached shocks' 0.05, then moved 4% of its standoff toward the body.
  // Still, falling density change above kBowShockSteadyTol: not steady until
  // it is under it twice.
  auto rows = history(40, [](int k) { return Sample{0.045 * std::pow(0.9, k - 1), 1e-4}; });
  for (auto& r : rows) {
    r.shock_x = kShockX;
    r.shock_cell = kCell;
  }
  int first_under = 0;
  for (std::size_t k = 0; k < rows.size() && first_under == 0; ++k)
    if (rows[k].drho_l2 < cfd::kBowShockSteadyTol) first_under = static_cast<int>(k) + 1;
  ASSERT_GT(first_under, static_cast<int>(cfd::kShockDriftRows));
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), first_under + 1);
  // The same history on an attached wedge is steady from the first rows.
  const scene::Scene attached = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n");
  cfd::SteadyState wedge_rule(cfd::SteadyCriteria::time_accurate(defaults()).for_body(attached));
  EXPECT_LT(steady_at(wedge_rule, rows), first_under);
}

TEST(ShockDriftGate, DriftingStandoffWithAFlatForceIsNotSteady) {
  // The measured defect: the M1.3 disc's shock crept upstream at ~0.9 radii
  // per flow-through while the force stayed within force_tol and the density
  // change sat at its floor. Here a slower creep, 0.1 radii per flow-through
  // (ten times the tolerance): the rule without the gate calls it steady at row 6, the
  // gate never.
  const auto rows = plateau_with_shock(
      30, [](int k) { return kShockX - 0.1 * kDiscRadius * k * kRowFlowThroughs; });
  cfd::SteadyState old_rule(cfd::SteadyCriteria::time_accurate(defaults()));
  EXPECT_EQ(steady_at(old_rule, rows), 6);
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), 0);
  EXPECT_NE(rule.why().find("shock not settled: shock drift -0.05"), std::string::npos)
      << rule.why();
  EXPECT_NEAR(rule.rows().back().shock_drift, -0.1 * kDiscRadius, 1e-12);
}

TEST(ShockDriftGate, DriftingStandoffBlocksTheToleranceBranchToo) {
  // Below steady_tol and force_tol from row 8 (as in
  // DecayingHistoryIsSteadyOnceBelowBothTolerancesTwice) but the shock moves.
  auto rows = history(30, [](int k) {
    return Sample{std::pow(0.5, k - 1), 0.1 * std::pow(0.5, k - 1)};
  });
  for (std::size_t k = 0; k < rows.size(); ++k) {
    rows[k].shock_x = kShockX - 4.0 * kDriftTol * rows[k].flow_throughs;
    rows[k].shock_cell = kCell;
  }
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), 0);
}

TEST(ShockDriftGate, FlickeringStandoffIsSteady) {
  // A captured shock flickering back and forth by one cell on every row: its
  // fitted slope is small against its scatter, so it does not count as
  // moving; steady where the old rule was.
  const auto rows =
      plateau_with_shock(30, [](int k) { return kShockX + (k % 2 == 0 ? 0.5 : -0.5) * kCell; });
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), 11);
  EXPECT_NE(rule.why().find("shock drift"), std::string::npos) << rule.why();
}

TEST(ShockDriftGate, SlowDriftWithinTheToleranceIsSteady) {
  const auto rows = plateau_with_shock(
      30, [](int k) { return kShockX - 0.5 * kDriftTol * k * kRowFlowThroughs; });
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), 11);
}

TEST(ShockDriftGate, NeedsAFullWindowOfRows) {
  // Quiet from the start with the shock still: the old rule is steady at row
  // 6; the gate first has a window at row kShockDriftRows (10), steady at 11.
  auto rows = history(20, [](int) { return Sample{1e-3, 1e-4}; });
  for (auto& r : rows) {
    r.shock_x = kShockX;
    r.shock_cell = kCell;
  }
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, rows), static_cast<int>(cfd::kShockDriftRows) + 1);
}

TEST(ShockDriftGate, AttachedWedgeIsJudgedAsBefore) {
  const scene::Scene attached = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n");
  const auto rows = plateau_with_shock(30, [](int k) { return kShockX - k; });
  cfd::SteadyState rule(cfd::SteadyCriteria::time_accurate(defaults()).for_body(attached));
  EXPECT_EQ(steady_at(rule, rows), 6);
  EXPECT_EQ(rule.why().find("shock"), std::string::npos) << rule.why();
}

TEST(ShockDriftGate, NoShockAheadOfTheNosePassesAShockFoundOnPartOfTheWindowDoesNot) {
  // Never measured (a shock attached to a pointed nose): nothing to drift.
  const auto none = plateau_with_shock(30, [](int) { return scene::kNaN; });
  cfd::SteadyState rule(blunt_criteria());
  EXPECT_EQ(steady_at(rule, none), 11);
  EXPECT_NE(rule.why().find("no shock ahead of the nose"), std::string::npos) << rule.why();
  // Found from row 8 on: the window holds only measured rows from row 17.
  const auto late = plateau_with_shock(30, [](int k) { return k < 8 ? scene::kNaN : kShockX; });
  cfd::SteadyState late_rule(blunt_criteria());
  EXPECT_EQ(steady_at(late_rule, late), 18);
}

}  // namespace
