#pragma once
// What a `pipeline run` will cost, before it runs: every grid's cells,
// solver steps and CPU seconds from a stated model (docs/verdict.md,
// "Sizing a run"), so a run that would take hours says so first.
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace pipeline {

struct GridEstimate {
  std::string name;  // uniform_h2, clustered_h1, ...
  double cells = 0, steps = 0, cpu_seconds = 0;
};

struct RunEstimate {
  std::vector<GridEstimate> grids;
  double predictor_cpu_seconds = 0;
  double total_cpu_seconds = 0;
};

// What the calibration table will add to a granular prediction's band (RMS
// out-of-sample errors; NaN: nothing, as when the scene sets its restitution):
// AppliedCalibration's angle_scatter_deg and bow_shock_relative_rms.
struct BandScatter {
  double angle_deg = scene::kNaN;
  double bow_relative = scene::kNaN;
};

// The scatter a run of `predictor` will take from its calibration table
// (`calibration_path`, "" for the scene's or the built-in one): the
// granular predictor's only; the scene is left as it is.
BandScatter band_scatter(const scene::Scene& s, const std::string& predictor,
                         const std::string& calibration_path);

RunEstimate estimate_run(const scene::Scene& s, const std::string& predictor,
                         const BandScatter& scatter = {});

// The model's CPU seconds (CFD and meshing) of the clustered grid at the
// finest of pipeline.levels round an attached shock leaving the body's nose
// at `angle_deg`, its band `band_half_angle_deg` either side: what a
// narrower band saves, priced while the granular predictor still averages.
// NaN for a scene without levels, a non-finite angle or width, or a grid
// meshgen would refuse or the model cannot price.
double clustered_finest_cpu(const scene::Scene& s, double angle_deg, double band_half_angle_deg);

// The table `--dry-run` prints.
std::string format_estimate(const RunEstimate& e, double budget_cpu_seconds);

// When the scene gives neither mesh.h_min nor mesh.h_max and the defaults'
// estimate exceeds pipeline.budget_cpu_seconds, coarsens both by one factor
// (at most kMaxCoarsening, sizes rounded to 2 significant figures) to the
// finest sizes whose estimate fits. Returns the line saying what it chose,
// or nothing when the scene keeps its sizes.
std::optional<std::string> fit_default_sizes_to_budget(scene::Scene& s,
                                                       const std::string& predictor,
                                                       const BandScatter& scatter = {});

// InputError when the estimate exceeds the budget, naming both and the way out.
void check_budget(const scene::Scene& s, const RunEstimate& e, bool force_budget);

}  // namespace pipeline
