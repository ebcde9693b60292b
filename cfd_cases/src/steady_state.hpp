#pragma once
// The steady-state rule of a rhoCentralFoam run, as a value: feed it the
// history rows (the measures between consecutive written times, in order)
// and ask whether the run is steady and why. No OpenFOAM needed, so the rule
// is tested on synthetic histories.
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "case_monitor.hpp"
#include "scene/params_cfd.hpp"
#include "scene/scene.hpp"

namespace cfd {

// How progress towards min_time is counted.
//  - flow_throughs: the row's simulated time (time-accurate stepping).
//  - iterations: the row's solver steps over steps_per_flow_through
//    ("iteration flow-throughs"); one row per window of iterations. Under
//    local time stepping the pseudo-time says nothing about how far the
//    solution has travelled (each cell takes its own step), the iteration
//    count does: at local Courant number maxCo a signal crosses the domain
//    in about steps_per_flow_through iterations.
enum class SteadyClock { flow_throughs, iterations };

struct SteadyCriteria {
  // Per flow-through (iterations clock: per iteration flow-through).
  double steady_tol = 0.05;  // L2 density change, relative to rho_inf
  double force_tol = 2e-3;   // relative body-force change
  double min_time = 1.0;     // (iteration) flow-throughs before steady may be declared
  int steady_checks = 2;     // consecutive rows that must pass
  SteadyClock clock = SteadyClock::flow_throughs;
  long steps_per_flow_through = 0;  // iterations clock only
  // The noise-floor branch (density change no longer falling, force
  // settled) counts only while the density change is below
  // plateau_cap x steady_tol (infinite: any plateau; steady_state.cpp says
  // why LTS needs one).
  double plateau_cap = std::numeric_limits<double>::infinity();
  // Bow-shock drift gate, for bodies whose shock may stand off (0: none, as
  // for attached shocks): no row passes while the shock on the stagnation
  // line (HistoryRow::shock_x) moves, by its least-squares slope over the
  // last kShockDriftRows rows, faster than shock_drift_tol times the
  // standoff (shock_nose_x - shock_x, the window's mean) per flow-through
  // and significantly (beyond kShockDriftSignificance standard errors of
  // the slope, so that flicker does not count as motion).
  double shock_drift_tol = 0.0;
  double shock_nose_x = 0.0;  // the body's nose, where the standoff is measured from

  // The scene's rule for time-accurate runs.
  static SteadyCriteria time_accurate(const scene::CfdParams& p);
  // The scene's rule under local time stepping: the same tolerances, with
  // progress counted in iterations, steps_per_flow_through per flow-through.
  static SteadyCriteria iteration_windows(const scene::CfdParams& p, long steps_per_flow_through);
  // These criteria for the scene's body: where its shock may stand off
  // (scene::shock_may_stand_off), the bow-shock rule: the drift gate on
  // (kShockDriftPerStandoff) and steady_tol at most kBowShockSteadyTol;
  // otherwise unchanged (the gate off).
  SteadyCriteria for_body(const scene::Scene& s) const;
  // The gate's drift tolerance (scene units per flow-through unit of
  // progress) for a shock at shock_x in cells of size `cell`.
  double shock_drift_tolerance(double shock_x, double cell) const;
};

// Rows over which the shock's drift is fitted (2 flow-throughs at the default
// write interval), its tolerance as a fraction of the standoff per
// flow-through, how many standard errors of the fitted slope a drift must
// exceed to count, and the density change a bow shock's run must get under
// (per flow-through, relative to rho_inf) outside its noise floor
// (steady_state.cpp says how they were chosen).
inline constexpr std::size_t kShockDriftRows = 10;
inline constexpr double kShockDriftPerStandoff = 0.002;
// The gate's tolerance is at least this many of the shock's cells
// (HistoryRow::shock_cell) per flow-through: 0.2% of a standoff under 10
// cells is below what its grid resolves. The disc references' standoffs span
// 16-49 cells, so the floor does not loosen them.
inline constexpr double kShockDriftCellsFloor = 0.02;
inline constexpr double kShockDriftSignificance = 3.0;
inline constexpr double kBowShockSteadyTol = 0.01;

class SteadyState {
 public:
  explicit SteadyState(SteadyCriteria c) : c_(c) {}

  // Appends the next row and updates the verdict. Once steady, stays steady.
  void add(const HistoryRow& row);

  bool steady() const { return steady_; }
  // Why the last row passed or failed (or why the run was declared steady).
  const std::string& why() const { return why_; }
  // Consecutive passing rows so far.
  int consecutive() const { return consecutive_; }
  // Progress of a row towards min_time, in the criteria's clock.
  double progress(const HistoryRow& row) const;
  const SteadyCriteria& criteria() const { return c_; }
  const std::vector<HistoryRow>& rows() const { return rows_; }

 private:
  struct ShockGate {
    bool ok = true;
    std::string why;  // empty when the gate does not apply
  };
  // The drift gate on the rows so far; sets the last row's shock_drift.
  ShockGate shock_gate();
  // The body force over the last window of rows (steady_state.cpp): its
  // least-squares slope per unit of progress and its scatter about that line,
  // both relative to the window's mean force; NaN until the window is full.
  struct ForceTrend {
    double slope = std::numeric_limits<double>::quiet_NaN();
    double flicker = std::numeric_limits<double>::quiet_NaN();
  };
  ForceTrend force_trend() const;
  // The last n rows (n <= rows_.size()) and their progress.
  std::span<const HistoryRow> window(std::size_t n) const;
  std::vector<double> window_progress(std::size_t n) const;
  // Least-squares slope of ln(drho_l2) per unit of progress over the same
  // window; NaN until the window is full.
  double density_trend() const;

  SteadyCriteria c_;
  std::vector<HistoryRow> rows_;
  int consecutive_ = 0;
  bool steady_ = false;
  std::string why_ = "no rows yet";
};

}  // namespace cfd
