#pragma once
// What this machine charges for a run's work, fitted on every run of one
// pipeline run (both families together):
//
//   cfd CPU  = steps x (per_step + per_cell_step x cells)
//   mesh CPU = mesh_base + mesh_per_cell x cells
//
// A run's cells and solver steps are deterministic (the same grid and
// solver reach steady state in the same number of steps on any run), but
// one CPU timing of it scatters by tens of percent on a shared machine.
// Pricing every run by the fitted model removes that per-run scatter from
// the comparison while keeping the machine's real cost per cell-step; the
// residual scatter of the fit is the measured size of one timing's noise,
// which the verdict's interval carries (equal_error.hpp).
#include <random>
#include <vector>

namespace pipeline {

struct WorkRun {
  long cells = 0;
  long steps = 0;
  double cfd_cpu = 0;   // measured solver CPU seconds
  double mesh_cpu = 0;  // measured meshing CPU seconds
};

struct WorkPrice {
  bool ok = false;
  int runs = 0;
  double per_step = 0, per_cell_step = 0;     // seconds
  double mesh_base = 0, mesh_per_cell = 0;    // seconds
  double cfd_log_sd = 0, mesh_log_sd = 0;     // scatter of one timing about the model (log)
  double cfd(const WorkRun& r) const;
  double mesh(const WorkRun& r) const;
};

// Needs at least three runs with positive cells, steps and CPU; `ok` false
// otherwise (the verdict then falls back to the measured CPU seconds).
WorkPrice fit_work_price(const std::vector<WorkRun>& runs);

// The same fit on the runs' CPU seconds each perturbed by one timing's
// scatter (a parametric bootstrap): one draw of the price's own uncertainty.
WorkPrice draw_work_price(const std::vector<WorkRun>& runs, const WorkPrice& fitted, std::mt19937_64& rng);

}  // namespace pipeline
