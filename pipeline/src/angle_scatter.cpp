#include "pipeline/angle_scatter.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "json_fields.hpp"
#include "pipeline/calibration_training.hpp"
#include "pipeline/rejudge.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "shockfit/group_interval.hpp"

namespace pipeline {

namespace {

namespace fs = std::filesystem;

// Runs of one measure share their averaging (flow-through times): the
// scatter belongs to the averaging the band is used at.
constexpr double kSameAveraging = 0.5;

// dir's subdirectories whose names start with `prefix`, sorted.
std::vector<fs::path> subdirs_named(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && e.path().filename().string().rfind(prefix, 0) == 0)
      out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

bool is_training_point(const CalibrationTable& t, double mach, double angle_deg) {
  return std::any_of(t.entries.begin(), t.entries.end(), [&](const CalibrationEntry& c) {
    return same_wedge({c.mach, c.angle_deg}, {mach, angle_deg});
  });
}

// The wedge the scene describes, refused where it cannot judge the table (a
// Mach number beyond the training range measures the extrapolation's error).
void check_unseen_wedge(const std::string& path, const scene::Scene& s, const CalibrationTable& t) {
  if (!s.body || s.body->kind != scene::BodyKind::wedge)
    throw scene::InputError(path + ": key 'body.kind': expected a wedge");
  const double mach = s.freestream.mach, angle = s.body->angle_deg;
  if (is_training_point(t, mach, angle))
    throw scene::InputError(path + ": a training point of the table (Mach " + format_number(mach) +
                            ", " + format_number(angle) + " deg): its error is in sample");
  if (is_case_study(s))
    throw scene::InputError(path + ": a case study's wedge: the case studies are predictions");
  const auto m = training_mach_range(t);
  const auto a = training_angle_range(t);
  if (!m || !a || !a->contains(angle))
    throw scene::InputError(path +
                            ": outside the table's training deflections: its error is an "
                            "extrapolation's, not the table's");
}

AngleCheckRun read_run(const fs::path& wedge_dir, const fs::path& seed_dir, double gas,
                       const CalibrationTable& t) {
  const std::string scene_path =
      (seed_dir.parent_path() / (seed_dir.filename().string() + ".yaml")).string();
  const scene::Scene s = scene::load_scene(scene_path);
  check_unseen_wedge(scene_path, s, t);
  const std::string sum_path = (seed_dir / "summary.json").string();
  const nlohmann::json j = read_run_summary(sum_path, "no summary (an unfinished run?)");
  if (j.value("shock", "") != "attached")
    throw scene::InputError(sum_path + ": key 'shock': not attached");
  const nlohmann::json& d = j.value("details", nlohmann::json::object());
  const double e = number_or_nan(d, "restitution");
  const double want =
      interpolate_restitution(t, s.freestream.mach, s.body->angle_deg).value_or(scene::kNaN);
  if (!is_applied_restitution(e, want))
    throw scene::InputError(sum_path + ": key 'details.restitution': " + format_number(e, 8) +
                            " is not the table's e " + format_number(want, 8) +
                            "; rerun the wedge with that table");
  AngleCheckRun r;
  r.wedge = wedge_dir.filename().string();
  r.angle = number_or_nan(j, "shock_angle_deg");
  r.half_width = number_or_nan(j, "shock_angle_ci_deg");
  r.gas = gas;
  r.flow_throughs = number_or_nan(d.value("averaging", nlohmann::json::object()), "flow_throughs");
  r.mach = s.freestream.mach;
  if (!std::isfinite(r.angle) || !std::isfinite(r.half_width))
    throw scene::InputError(sum_path + ": key 'shock_angle_ci_deg': no angle with an interval");
  return r;
}

}  // namespace

AngleScatter angle_scatter_of(const std::vector<AngleCheckRun>& runs) {
  if (runs.size() < kMinAngleCheckRuns)
    throw scene::InputError("calibrate: --angle-check-runs: " + std::to_string(runs.size()) +
                            " runs, at least " + std::to_string(kMinAngleCheckRuns) +
                            " needed for a scatter");
  double err2 = 0, noise2 = 0;
  std::set<std::string> wedges;
  std::vector<double> averaging;
  for (const AngleCheckRun& r : runs) {
    const double err = r.angle - r.gas, sd = r.half_width / shockfit::kNormal95;
    err2 += err * err;
    noise2 += sd * sd;
    wedges.insert(r.wedge);
    averaging.push_back(r.flow_throughs);
  }
  const auto n = static_cast<double>(runs.size());
  std::nth_element(averaging.begin(), averaging.begin() + static_cast<long>(averaging.size() / 2),
                   averaging.end());
  AngleScatter a;
  a.deg = std::sqrt(std::max(0.0, (err2 - noise2) / n));
  a.rms_deg = std::sqrt(err2 / n);
  a.flow_throughs = averaging[averaging.size() / 2];
  a.runs = static_cast<int>(runs.size());
  a.wedges = static_cast<int>(wedges.size());
  const auto [lo, hi] = std::minmax_element(
      runs.begin(), runs.end(),
      [](const AngleCheckRun& x, const AngleCheckRun& y) { return x.mach < y.mach; });
  a.mach_low = lo->mach;
  a.mach_high = hi->mach;
  return a;
}

nlohmann::json calibrate_angle_scatter(const std::vector<std::string>& dirs,
                                       const std::string& table_path) {
  const std::string path = table_path.empty() ? builtin_calibration_path() : table_path;
  CalibrationTable table = read_calibration(path);  // a bad table fails before anything
  if (!table.model)
    throw scene::InputError(path +
                            ": key 'model': an old table (entries only) has no fit to judge");
  std::vector<AngleCheckRun> runs;
  for (const auto& dir : dirs) {
    if (!fs::is_directory(dir))
      throw scene::InputError(dir +
                              ": --angle-check-runs: no such directory (an angle_check.sh "
                              "output expected)");
    for (const fs::path& w : subdirs_named(dir, "oos_")) {
      const nlohmann::json gas = read_run_summary((w / "gas" / "summary.json").string(),
                                                  "no gas angle (an unfinished wedge?)");
      for (const fs::path& sd : subdirs_named(w, "seed"))
        runs.push_back(read_run(w, sd, number_or_nan(gas, "shock_angle_deg"), table));
    }
  }
  for (const AngleCheckRun& r : runs)
    if (!(std::abs(r.flow_throughs - runs.front().flow_throughs) <= kSameAveraging))
      throw scene::InputError("calibrate: --angle-check-runs: " + r.wedge + " averaged " +
                              format_number(r.flow_throughs) + " flow-through times, " +
                              runs.front().wedge + " " + format_number(runs.front().flow_throughs) +
                              ": the scatter belongs to one averaging");
  // Inside the ranges, the table's own error; beyond its Mach range, the
  // extrapolation's, on one side: one measure never mixes them. Runs all
  // beyond the Mach numbers the inside scatter was measured on, on one side,
  // measure that side apart too (a table extended there by `--extend`).
  // -1 below `r`, 0 inside, 1 above.
  const auto side_of = [](const MachRange& r, double mach) {
    return r.contains(mach) ? 0 : mach > r.high ? 1 : -1;
  };
  const auto range = training_mach_range(table);
  const auto side = [&](const AngleCheckRun& r) { return side_of(*range, r.mach); };
  for (const AngleCheckRun& r : runs)
    if (side(r) != side(runs.front()))
      throw scene::InputError(
          "calibrate: --angle-check-runs: " + r.wedge + " (Mach " + format_number(r.mach) +
          ") and " + runs.front().wedge + " (Mach " + format_number(runs.front().mach) +
          ") lie on different sides of the training Mach range " + format_number(range->low) + "-" +
          format_number(range->high) +
          ": the table's error inside it and the extrapolation's beyond it are measured apart");
  const auto measured = scatter_mach_range(table);
  const int past_first = side_of(*measured, runs.front().mach);
  const bool all_past = table.angle_scatter.has_value() && past_first != 0 &&
                        std::all_of(runs.begin(), runs.end(), [&](const AngleCheckRun& r) {
                          return side_of(*measured, r.mach) == past_first;
                        });
  const AngleScatter a = angle_scatter_of(runs);
  const bool beyond = side(runs.front()) != 0 || all_past;
  (beyond ? table.angle_scatter_beyond : table.angle_scatter) = a;
  // A beyond block is measured past the inside block's Mach numbers; a new
  // inside block that reaches its runs leaves it nothing to stand for.
  if (!beyond && table.angle_scatter_beyond &&
      !(table.angle_scatter_beyond->mach_low > a.mach_high ||
        table.angle_scatter_beyond->mach_high < a.mach_low))
    table.angle_scatter_beyond.reset();
  write_calibration(table, path);
  return {{"table", path},
          {"block", beyond ? "angle_scatter_beyond_mach" : "angle_scatter"},
          {"angle_scatter_deg", a.deg},
          {"rms_deg", a.rms_deg},
          {"flow_throughs", a.flow_throughs},
          {"runs", a.runs},
          {"wedges", a.wedges},
          {"mach_low", a.mach_low},
          {"mach_high", a.mach_high}};
}

}  // namespace pipeline
