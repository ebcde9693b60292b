#pragma once
// The table's own attached-angle error, measured on unseen wedges predicted
// with the table at the default averaging (bench/calibration_oos/
// angle_check.sh directories), written into the table's `angle_scatter`
// block (docs/calibration.md, "The band's table error").
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pipeline/calibration.hpp"

namespace pipeline {

// One unseen-wedge run: its granular angle and 95% half-width, the gas's
// exact angle (deg) and the flow-through times it averaged.
struct AngleCheckRun {
  std::string wedge;
  double angle = scene::kNaN, half_width = scene::kNaN, gas = scene::kNaN;
  double flow_throughs = scene::kNaN;
  double mach = scene::kNaN;  // free stream
};

// sqrt(mean error^2 - mean (half-width / 1.96)^2), floored at zero, over the
// runs; the wedges counted by name. InputError for fewer than kMinAngleCheckRuns.
inline constexpr std::size_t kMinAngleCheckRuns = 12;
AngleScatter angle_scatter_of(const std::vector<AngleCheckRun>& runs);

// `pipeline calibrate --angle-check-runs DIR...`: reads every DIR/oos_*/
// (gas/summary.json and seed*/summary.json of `pipeline predict`), refuses
// (InputError naming the file) a run not at the table's e, a training point,
// a case study, a wedge outside the training deflections, a run whose shock
// is not attached, runs of differing averaging, and runs on different sides
// of the training Mach range, and writes the block into the table at
// table_path (default: the built-in one), keeping everything else: runs
// inside the Mach range give `angle_scatter`, runs all beyond it on one side
// `angle_scatter_beyond_mach`.
// Runs nothing. Returns the figures.
nlohmann::json calibrate_angle_scatter(const std::vector<std::string>& dirs,
                                       const std::string& table_path);

}  // namespace pipeline
