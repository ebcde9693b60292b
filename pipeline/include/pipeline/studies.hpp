#pragma once
// Parameter sweeps, the e calibration, and the case studies.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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
  // Training wedges. Default: generated on the machs x angles_deg grid
  // (attached at gamma 1.4, case studies left out) with every other scene key
  // at its default, as the case studies have them. Seven Machs: the coarser
  // 4 x 3 grid missed a bend of e in ln M, and its table left 16 unseen wedges
  // 0.48 deg RMS off against 0.32 with seven (docs/calibration.md, "Result
  // (2026-12-05, shipped)"). Deflections up to 26 deg: beyond 20 the
  // crossings turn up towards detachment, and a table trained only to 20 put
  // wedges at 21-26.5 deg 1.2 deg RMS off (docs/calibration.md, "Deflections
  // up to 26 deg"). Steps of 1.5 deg from 20 to 26: the turn comes earlier
  // at low Mach number, which the local correction follows from the denser
  // points (docs/calibration.md, "A local correction").
  std::vector<std::string> scenes;
  std::vector<double> machs{2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0};
  std::vector<double> angles_deg{8.0, 11.0, 14.0, 17.0, 20.0, 21.5, 23.0, 24.5, 26.0};
  // The crossings lie near 0.96-0.99, where angle(e) is strongly convex
  // (M2.5/14: 32 deg at 0.98, 49 at 1): the sweep is coarse and then
  // `refinements` runs bisect the bracketing interval (or extend the sweep
  // down by one step when every angle is above the gas angle).
  std::vector<double> restitutions{0.96, 0.98, 1.0};
  int refinements = 1;
  // Runs per swept e at seeds sharing no replica, averaged: one run's angle
  // scatters by 0.1-0.25 deg (sd), as much as 0.001 of e moves it. Three
  // seeds halve the crossings' intervals but left the out-of-sample angle
  // error where one seed has it (docs/calibration.md, "Three seeds per e").
  int seeds = 1;
  // Flow-through times each generated training wedge averages; unset: the
  // default's 4 (calibration_training.cpp). Scenes given with `scenes` carry
  // their own.
  std::optional<double> averaging;
  std::string table_path;           // default: builtin_calibration_path()
  std::string markdown_path;        // default: <out_dir>/calibration.md
  int jobs = 1, np = 1;
  // Out-of-sample checks: each training wedge at its leave-one-out e, and the
  // wedge case studies at the fitted e, both with seeds the fit never used.
  bool verify = true;
};
nlohmann::json run_calibration(const CalibrateOptions& o);
// The same fit from crossings measured elsewhere, no granular run: the
// `crossings` of pipeline parametric's parametric_calibration.json, the
// `points` of a calibrate run's calibration.json, or a table's entries
// (.yaml), joined; a wedge given twice is an error, the case studies are left
// out. Writes the table (default: the built-in one). With `extend` the first
// source is a table being extended: the local correction keeps its widths,
// so crossings added beyond its range leave e inside it where its own
// correction had it, and its measured angle scatter is kept.
nlohmann::json calibrate_from_points(const std::vector<std::string>& sources,
                                     const std::string& table_path, bool extend = false);

struct StudiesOptions {
  std::string out_dir;
  std::vector<std::string> scenes;  // default: every pipeline/cases/*.yaml
  std::string docs_table;           // default: <source>/docs/case_studies.md
  int np = 1;
};
nlohmann::json run_studies(const StudiesOptions& o);

std::vector<std::string> case_study_scenes();
// Whether s has a case study's body at its Mach number: what no fit may train
// or measure its scatter on.
bool is_case_study(const scene::Scene& s);

}  // namespace pipeline
