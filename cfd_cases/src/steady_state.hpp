#pragma once
// The steady-state rule of a rhoCentralFoam run, as a value: feed it the
// history rows (the measures between consecutive written times, in order)
// and ask whether the run is steady and why. No OpenFOAM needed, so the rule
// is tested on synthetic histories.
#include <string>
#include <vector>

#include "case_monitor.hpp"
#include "scene/params_cfd.hpp"

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

  // The scene's rule for time-accurate runs.
  static SteadyCriteria time_accurate(const scene::CfdParams& p);
  // The scene's rule under local time stepping: the same tolerances, with
  // progress counted in iterations, steps_per_flow_through per flow-through.
  static SteadyCriteria iteration_windows(const scene::CfdParams& p, long steps_per_flow_through);
};

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
  SteadyCriteria c_;
  std::vector<HistoryRow> rows_;
  int consecutive_ = 0;
  bool steady_ = false;
  std::string why_ = "no rows yet";
};

// Whether the density change has settled at the noise floor of a captured
// shock (see steady_state.cpp); exposed for tests.
bool at_noise_floor(const std::vector<HistoryRow>& rows, double force_tol);

}  // namespace cfd
