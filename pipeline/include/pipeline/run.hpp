#pragma once
// `pipeline run`: granular -> shockfit -> meshgen (clustered and uniform
// families) -> rhoCentralFoam on each grid -> comparison and report.
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace pipeline {

struct RunOptions {
  std::string out_dir;
  int np = 1;                       // MPI ranks for granular replicas and OpenFOAM
  std::set<std::string> force;      // stages to rerun: granular, shockfit, meshgen, cfd, report, all
  std::string calibration_path;     // restitution table ("" = scene's or built-in)
};

// Applies the calibration table when the scene leaves granular.restitution
// unset (wedges only); returns a note for the report ("" if nothing changed).
std::string apply_calibration(scene::Scene& s, const std::string& table_path);

// Runs everything; returns the pipeline summary (also DIR/summary.json).
nlohmann::json run_pipeline(scene::Scene s, const RunOptions& o);

// Granular + shockfit only (sweeps and calibration). Returns shockfit's summary
// merged with granular's wall time.
nlohmann::json run_prediction(const scene::Scene& s, const std::string& out_dir, int np,
                              bool force = false);

// Path of the built-in calibration table (pipeline/calibration.yaml in the source tree).
std::string builtin_calibration_path();

}  // namespace pipeline
