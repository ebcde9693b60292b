#include "steady_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>

#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/units.hpp"

namespace cfd {

namespace {
// Slack on min_time, in flow-through times (written times are rounded).
constexpr double kMinTimeSlack = 1e-6;

// Rows per window of the force's trend and the noise floor, and how much the
// density change must still be falling per flow-through to count as
// converging.
constexpr std::size_t kPlateauChecks = 5;
constexpr double kStillFalling = 0.8;

// Under LTS a clustered grid converges on two clocks: its coarse cells
// within an iteration flow-through, the fine shock band (small local steps)
// several later. In between, the density change stalls on a false plateau
// far above the noise floor: 0.43-0.48 per iteration flow-through on the
// finest clustered M5/20 grid, whose L1 density error was still falling from
// 0.035 to 0.006, against a floor of 0.04-0.07 once settled (0.03-0.15 over
// Mach 3-8 time-accurately). A plateau counts under LTS only below this
// multiple of steady_tol.
constexpr double kLtsPlateauCap = 4.0;

// The least-squares line v = mean + slope (t - mean of t) through a window,
// with the sum of squared residuals about it and the spread of t
// (sum of (t - mean)^2; slope and sse are NaN when it is 0).
struct WindowLine {
  double mean = 0, slope = scene::kNaN, sse = scene::kNaN, stt = 0;
};
WindowLine fit_window_line(const std::vector<double>& t, const std::vector<double>& v) {
  const double n = static_cast<double>(t.size());
  double t_mean = 0;
  WindowLine l;
  for (std::size_t i = 0; i < t.size(); ++i) {
    t_mean += t[i] / n;
    l.mean += v[i] / n;
  }
  double stv = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double dt = t[i] - t_mean;
    l.stt += dt * dt;
    stv += dt * (v[i] - l.mean);
  }
  if (!(l.stt > 0)) return l;
  l.slope = stv / l.stt;
  l.sse = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double r = v[i] - l.mean - l.slope * (t[i] - t_mean);
    l.sse += r * r;
  }
  return l;
}

std::string force_why(const HistoryRow& row, double slope, double flicker, double tol) {
  if (row.dforce < tol) return fmt::format("dF {:.3g} < {:.3g}", row.dforce, tol);
  return fmt::format("force trend {:.3g}, flicker {:.3g} <= {:.3g} (dF {:.3g})", slope, flicker,
                     tol, row.dforce);
}
}  // namespace

SteadyCriteria SteadyCriteria::time_accurate(const scene::CfdParams& p) {
  SteadyCriteria c;
  c.steady_tol = p.steady_tol;
  c.force_tol = p.force_tol;
  c.min_time = p.min_time;
  c.steady_checks = p.steady_checks;
  c.clock = SteadyClock::flow_throughs;
  return c;
}

SteadyCriteria SteadyCriteria::for_body(const scene::Scene& s) const {
  SteadyCriteria c = *this;
  if (!scene::shock_may_stand_off(s)) {
    c.shock_drift_tol = 0.0;
    return c;
  }
  c.shock_drift_tol = kShockDriftPerStandoff;
  c.shock_nose_x = scene::make_body(*s.body).nose.x;
  c.steady_tol = std::min(c.steady_tol, kBowShockSteadyTol);
  return c;
}

// A shock behind the nose (a body whose nose is not foremost) is held to its
// distance's size all the same. A standoff of a few cells is not resolved to
// a fraction of itself: the tolerance is never below kShockDriftCellsFloor
// cells per flow-through.
double SteadyCriteria::shock_drift_tolerance(double shock_x, double cell) const {
  return std::max(shock_drift_tol * std::abs(shock_nose_x - shock_x), kShockDriftCellsFloor * cell);
}

SteadyCriteria SteadyCriteria::iteration_windows(const scene::CfdParams& p,
                                                 long steps_per_flow_through) {
  SteadyCriteria c = time_accurate(p);
  c.clock = SteadyClock::iterations;
  c.steps_per_flow_through = std::max(1L, steps_per_flow_through);
  c.plateau_cap = kLtsPlateauCap;
  return c;
}

// A converged shock solution does not bring the density change to zero: cells
// in the captured shock flicker (rhoCentralFoam's limiter), leaving a floor
// that grows with shock strength (0.03 per flow-through at Mach 3, 0.05 at
// Mach 5, 0.15 at Mach 8) while the body force is steady to 1e-3. So a run is
// also steady once the density change has stopped falling and the body force
// has settled over the last window. "Stopped falling": the least-squares
// slope of ln(drho) over the window is above ln(kStillFalling) per
// flow-through. One window, not the mean of one window against the one
// before, which held every run on the floor 2 flow-throughs after it got
// there (docs/cfd_cases.md, "The force's trend").
double SteadyState::density_trend() const {
  if (rows_.size() < kPlateauChecks) return scene::kNaN;
  std::vector<double> log_drho;
  for (const HistoryRow& r : window(kPlateauChecks)) {
    if (!(r.drho_l2 > 0)) return scene::kNaN;
    log_drho.push_back(std::log(r.drho_l2));
  }
  return fit_window_line(window_progress(kPlateauChecks), log_drho).slope;
}

// The body force of a converged captured-shock solution flickers too: the
// limiter moves a cell's worth of pressure back and forth, 0.05-0.2% of the
// force on the recorded wedges (docs/cfd_cases.md, "The force's trend"). The
// change between two written times 0.2 flow-throughs apart, per
// flow-through, turns that into 0.25-1% (above force_tol): such grids ran
// on to the noise-floor branch or end_time, 1.8 to 5 flow-throughs for the
// same settled state. Over a window of kPlateauChecks rows the force's
// least-squares trend sees drift and not flicker; the scatter about the
// line bounds the flicker, so a force swinging by more than force_tol is
// never settled whatever its trend.
SteadyState::ForceTrend SteadyState::force_trend() const {
  if (rows_.size() < kPlateauChecks) return {};
  std::vector<double> fx, fy;
  for (const HistoryRow& r : window(kPlateauChecks)) {
    fx.push_back(r.force.x);
    fy.push_back(r.force.y);
  }
  const std::vector<double> t = window_progress(kPlateauChecks);
  const WindowLine x = fit_window_line(t, fx), y = fit_window_line(t, fy);
  const double f_mean = std::hypot(x.mean, y.mean);
  if (!(x.stt > 0) || !(f_mean > 0)) return {};
  const double n = static_cast<double>(kPlateauChecks);
  return {std::hypot(x.slope, y.slope) / f_mean, std::sqrt((x.sse + y.sse) / (n - 2)) / f_mean};
}

std::span<const HistoryRow> SteadyState::window(std::size_t n) const {
  return std::span<const HistoryRow>(rows_).last(n);
}

std::vector<double> SteadyState::window_progress(std::size_t n) const {
  std::vector<double> t;
  for (const HistoryRow& r : window(n)) t.push_back(progress(r));
  return t;
}

double SteadyState::progress(const HistoryRow& row) const {
  if (c_.clock == SteadyClock::iterations)
    return static_cast<double>(row.steps) / static_cast<double>(c_.steps_per_flow_through);
  return row.flow_throughs;
}

// Neither branch above sees a bow shock creeping upstream: the body force
// barely moves while the shock's standoff grows (a Mach 1.3 disc with a
// zeroGradient outflow drifted 0.9 radii per flow-through and was called
// steady by the noise floor). So where a shock may stand off the body, its
// position on the stagnation line must also hold still: the least-squares
// slope over the last kShockDriftRows rows must stay within
// kShockDriftPerStandoff of the standoff per flow-through, or be no more
// than kShockDriftSignificance standard errors (from the residuals about the
// fitted line) from zero. The second clause makes a shock flickering back and
// forth by a cell steady: its fitted slope is small against its scatter.
// The tolerance is the standoff's, not the body's: at a body-length
// tolerance (0.01 per flow-through) and the attached shocks' density
// tolerance (0.05) every disc reference stopped at 7-10 flow-throughs with
// its shock still approaching the body by 1-3% of the standoff per
// flow-through, and a disc at Mach 5.5 run on settled 4.3% nearer the body
// than where it stopped, after pausing for a flow-through on the way
// (docs/reliability.md, "Bow shocks that stopped early"). Hence also
// kBowShockSteadyTol: a bow shock on a converging grid has no flicker floor
// at 0.03-0.05 (its density change fell to 5e-4 per flow-through), so a
// density change of that size says it is still moving.
SteadyState::ShockGate SteadyState::shock_gate() {
  if (!(c_.shock_drift_tol > 0)) return {};
  const std::size_t n = kShockDriftRows;
  if (rows_.size() < n)
    return {false, fmt::format("shock position over {} of {} rows", rows_.size(), n)};
  std::vector<double> x;
  double cell = 0.0;  // the coarsest cell the shock sat in over the window
  for (const HistoryRow& r : window(n)) {
    if (std::isfinite(r.shock_x)) x.push_back(r.shock_x);
    if (std::isfinite(r.shock_cell)) cell = std::max(cell, r.shock_cell);
  }
  const std::size_t measured = x.size();
  // No shock ahead of the nose in the whole window: one attached to a
  // pointed nose, nothing on the line to drift.
  if (measured == 0) return {true, "no shock ahead of the nose"};
  if (measured < n)
    return {false, fmt::format("a shock ahead of the nose on {} of the last {} rows", measured, n)};
  const WindowLine line = fit_window_line(window_progress(n), x);
  if (!(line.stt > 0)) return {false, "shock drift over a window of no length"};
  const double slope = line.slope;
  // Standard error of the slope, with the two fitted parameters taken off.
  const double se = std::sqrt(line.sse / static_cast<double>(n - 2) / line.stt);
  rows_.back().shock_drift = slope;
  const double tol = c_.shock_drift_tolerance(line.mean, cell);
  const bool moving = std::abs(slope) > tol && std::abs(slope) > kShockDriftSignificance * se;
  const char* per = c_.clock == SteadyClock::iterations ? "iteration flow-through" : "flow-through";
  return {!moving,
          fmt::format("shock drift {:.3g} +- {:.2g} per {} (tol {:.3g}, {:.2g} of the standoff)",
                      slope, se, per, tol, c_.shock_drift_tol)};
}

void SteadyState::add(const HistoryRow& row) {
  rows_.push_back(row);
  const char* unit =
      c_.clock == SteadyClock::iterations ? "iteration flow-throughs" : "flow-throughs";
  const double at = progress(row);
  const bool early = at < c_.min_time - kMinTimeSlack;
  const ForceTrend trend = force_trend();
  const bool force_still = trend.slope <= c_.force_tol && trend.flicker <= c_.force_tol;
  const bool below_tol = row.drho_l2 < c_.steady_tol && (row.dforce < c_.force_tol || force_still);
  const bool plateau = !below_tol && force_still && row.drho_l2 < c_.plateau_cap * c_.steady_tol &&
                       density_trend() >= std::log(kStillFalling);
  const ShockGate gate = shock_gate();
  const bool ok = !early && (below_tol || plateau) && gate.ok;
  consecutive_ = ok ? consecutive_ + 1 : 0;
  if (steady_) return;
  const std::string shock = gate.why.empty() ? "" : "; " + gate.why;
  if (early) {
    why_ = fmt::format("too early: {:.3g} of {:.3g} {}", at, c_.min_time, unit);
  } else if (ok) {
    why_ = fmt::format(
        "{} ({} of {} checks): {}{}", consecutive_ >= c_.steady_checks ? "steady" : "passing",
        consecutive_, c_.steady_checks,
        below_tol ? fmt::format("drho {:.3g} < {:.3g}, {}", row.drho_l2, c_.steady_tol,
                                force_why(row, trend.slope, trend.flicker, c_.force_tol))
                  : "density change at its noise floor, body force within force_tol",
        shock);
  } else if (below_tol || plateau) {
    why_ = fmt::format("shock not settled: {} at {:.3g} {}", gate.why, at, unit);
  } else {
    why_ = fmt::format(
        "changing: drho {:.3g} (tol {:.3g}), dF {:.3g}, force trend {:.3g}, flicker {:.3g} (tol "
        "{:.3g}) at {:.3g} {}{}",
        row.drho_l2, c_.steady_tol, row.dforce, trend.slope, trend.flicker, c_.force_tol, at, unit,
        shock);
  }
  steady_ = consecutive_ >= c_.steady_checks;
}

}  // namespace cfd
