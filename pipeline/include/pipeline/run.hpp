#pragma once
// `pipeline run`: a shock predictor (granular gas + shockfit by default) ->
// meshgen (clustered and uniform families) -> rhoCentralFoam on each grid ->
// verdict and report.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "pipeline/calibration.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace pipeline {

struct RunOptions {
  std::string out_dir;
  int np = 1;                    // MPI ranks for granular replicas and OpenFOAM
  std::set<std::string> force;   // stages to rerun: granular, shockfit, meshgen, cfd, report, all
  std::string calibration_path;  // restitution table ("" = scene's or built-in)
  std::string predictor = "granular";  // predictor.hpp's registry
  // summary<suffix>.json and report<suffix>.md: the league keeps one per
  // predictor beside the shared grids. Default: "" for granular, else _<name>.
  std::optional<std::string> output_suffix;
};

// What a calibration table gave a scene.
struct AppliedCalibration {
  std::string note;                  // for the report ("" if nothing changed)
  double cpu_seconds = scene::kNaN;  // what the table cost to make (NaN: not recorded, or no table)
  // The table's out-of-sample angle scatter (deg, RMS) when the restitution
  // came from it and the body has a wedge angle; NaN otherwise.
  double angle_scatter_deg = scene::kNaN;
  // Its bow shocks' out-of-sample relative distance error (RMS) when the
  // restitution came from it (for every body: the predictor uses it on a
  // shock it finds detached); NaN otherwise.
  double bow_shock_relative_rms = scene::kNaN;
  // The scene's Mach number lies outside the table's training range: e(M)
  // is extrapolated, and the prediction's error there is unmeasured.
  bool outside_training_mach = false;
  // The body's shape's station bias when it runs at the table's blunt law
  // and the table measured one (its relative_rms is then bow_shock_relative_rms).
  std::optional<BowStationBias> station_bias = std::nullopt;
};
// A table the user named (`table_path`, or the scene's pipeline.calibration)
// must exist: silently running uncalibrated would change every result without
// a word. Only the built-in table may be absent. InputError naming the file
// (and the scene's key) otherwise.
void require_named_calibration(const scene::Scene& s, const std::string& table_path);
// Applies the calibration table when the scene leaves granular.restitution
// unset; bodies without a wedge angle take its Mach-only fit.
AppliedCalibration apply_calibration(scene::Scene& s, const std::string& table_path);

// The family name of a predictor's clustered grids in runs[] ("clustered"
// for granular, "clustered-<name>" otherwise).
std::string clustered_family(const std::string& predictor);

// Runs everything; returns the pipeline summary (also DIR/summary.json).
nlohmann::json run_pipeline(scene::Scene s, const RunOptions& o);

// Granular + shockfit only (sweeps and calibration). Returns shockfit's summary
// merged with granular's wall time. angle_scatter_deg: the calibration
// table's, for `target_half_width: band` (precision_goal).
nlohmann::json run_prediction(const scene::Scene& s, const std::string& out_dir, int np,
                              bool force = false, double angle_scatter_deg = scene::kNaN);
// The same at restitution e and seed (the calibrations' sweeps); RunError
// when interrupted (finished runs stay cached, so a rerun resumes).
nlohmann::json run_prediction_at(const scene::Scene& s, double e, std::uint64_t seed,
                                 const std::string& out_dir, int np);

// The named predictor's shock for the scene, its stages cached under
// out_dir (granular: out_dir itself; others: out_dir/predict/<name>).
struct Prediction;
Prediction predict_shock(const scene::Scene& s, const std::string& predictor,
                         const std::string& out_dir, int np, bool force = false,
                         double calibration_angle_scatter_deg = scene::kNaN,
                         double calibration_bow_shock_relative_rms = scene::kNaN,
                         const BowStationBias* bow_station_bias = nullptr);

// Path of the built-in calibration table (pipeline/calibration.yaml in the source tree).
std::string builtin_calibration_path();

}  // namespace pipeline
