#pragma once
// Parameter sweeps, the e calibration, and the case studies.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace pipeline {

struct Vary {
  std::string key;              // dotted scene key, e.g. granular.restitution
  std::vector<std::string> values;
};
Vary parse_vary(const std::string& arg);  // "KEY=v1,v2,..."; InputError if malformed

// The scene file with `key` set to `value` at each (key, value) pair,
// re-parsed (so bad values are reported like any scene error).
scene::Scene scene_with(const std::string& scene_path, const std::vector<std::pair<std::string, std::string>>& sets);

struct SweepOptions {
  std::string out_dir;
  int jobs = 1;   // cases run at once, as processes
  int np = 1;     // threads per case
};
// Granular + shockfit over the grid of values; writes sweep.csv, sweep.json
// and sweep.png. Returns the rows.
nlohmann::json run_sweep(const std::string& scene_path, const std::vector<Vary>& vary, const SweepOptions& o);

struct CalibrateOptions {
  std::string out_dir;
  std::vector<std::string> scenes;  // wedge scenes (default: the three wedge case studies)
  std::vector<double> restitutions{0.6, 0.7, 0.8, 0.9, 1.0};
  std::string table_path;           // default: builtin_calibration_path()
  int jobs = 1, np = 1;
  bool verify = true;               // rerun at the calibrated e and record the angle
};
nlohmann::json run_calibration(const CalibrateOptions& o);

struct StudiesOptions {
  std::string out_dir;
  std::vector<std::string> scenes;  // default: every pipeline/cases/*.yaml
  std::string docs_table;           // default: <source>/docs/case_studies.md
  int np = 1;
};
nlohmann::json run_studies(const StudiesOptions& o);

std::vector<std::string> case_study_scenes();

}  // namespace pipeline
