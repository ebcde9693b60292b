#pragma once
#include <optional>
#include <string>
#include <vector>

namespace scene {

// `pipeline:` section: the clustered-vs-uniform comparison.
struct PipelineParams {
  // Refinement levels: each family is meshed at h_min x level (and h_max x
  // level), coarse to fine. Five levels about sqrt(2) apart span 16x in cells
  // (more on clustered grids): enough for a log-log fit of error against cost
  // with three degrees of freedom, at 1.5x the cost of the finest grid alone.
  std::vector<double> levels{4.0, 2.8, 2.0, 1.4, 1.0};
  // Restitution table written by `pipeline calibrate`; used when the scene
  // does not set granular.restitution. "" = the built-in pipeline/calibration.yaml.
  std::string calibration;
  bool cfd = true;
  // Bodies without an exact field solution (blunt bodies, detached shocks)
  // get one more uniform grid, finer than every family member and in
  // neither family, for Richardson extrapolation of standoff and drag.
  bool reference_grid = true;
  std::optional<double> reference_level;  // default: half the finest level
  // CPU seconds a run may be estimated to cost before it asks for
  // --force-budget (one CPU hour: a scene that needs more is sized on purpose).
  double budget_cpu_seconds = 3600.0;  // false: stop after meshing (granular + shockfit + meshgen only)
};

}  // namespace scene
