#pragma once
// `pipeline predict` (a predictor alone) and `pipeline league` (every
// predictor's clustered family against the uniform family, per scene).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace pipeline {

struct PredictOptions {
  std::string predictor = "granular";
  std::string out_dir;
  std::string calibration_path;
  int np = 1;
};
// DIR/shock.csv, DIR/summary.json (predictor, shock, angle or standoff with
// its interval, cpu_seconds, the reference and the error where the scene
// has one) and DIR/shock.png.
nlohmann::json run_predict(scene::Scene s, const PredictOptions& o);

struct LeagueOptions {
  std::string out_dir;
  std::vector<std::string> scenes;      // default: the case studies
  std::vector<std::string> predictors;  // default: every registered predictor
  std::string docs_page;                // default: <source>/docs/league.md
  int np = 1;
  // Build the page from the summaries already in out_dir (summary_<name>.json
  // per scene) without running anything.
  bool from_runs = false;
};
// Per scene: every predictor's family against the uniform family, then the
// granular family head to head against each other predictor's family (their
// total CPU at the granular family's finest error, each with its own
// predictor's cost).
nlohmann::json run_league(const LeagueOptions& o);

}  // namespace pipeline
