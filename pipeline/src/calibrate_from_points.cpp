// `pipeline calibrate --from-points FILE...`: the e(M[, theta]) fit trained
// on crossings measured elsewhere, with no granular run: the `crossings` of
// `pipeline parametric`'s parametric_calibration.json, the `points` of a
// `pipeline calibrate` run's calibration.json, or the entries of a table
// (YAML). Several sources join into one training set, so a table can be
// extended by the crossings of new training wedges without rerunning its
// own. The table records where its points came from: a calibration holds
// only for the granular settings its points were measured with.
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "pipeline/calibration.hpp"
#include "pipeline/calibration_report.hpp"
#include "pipeline/calibration_training.hpp"
#include "pipeline/restitution_fit.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {
// The case studies are predictions, never training points.
bool is_case_study(double mach, double angle_deg) {
  const WedgePoint cases[] = {{3, 10}, {4, 15}, {5, 20}};
  for (const auto& c : cases)
    if (same_wedge({mach, angle_deg}, c)) return true;
  return false;
}

struct Source {
  std::vector<CalibrationEntry> crossings;
  double cpu_seconds = std::nan("");
};

// A table's entries: its crossings at the digits it holds.
Source table_source(const std::string& path) {
  Source s;
  const auto t = read_calibration(path);
  for (const auto& e : t.entries)
    s.crossings.push_back(
        crossing_entry(e.mach, e.angle_deg, e.restitution, e.restitution_ci, e.gas_angle_deg));
  s.cpu_seconds = t.cpu_seconds;
  if (s.crossings.empty())
    throw scene::InputError(path + ": key 'entries': the table holds no crossings");
  return s;
}

// parametric_calibration.json (`crossings`) or calibrate's calibration.json
// (`points`; a training wedge whose sweep found no crossing has none).
Source json_source(const std::string& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(scene::read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw scene::InputError(path + ": not JSON: " + e.what());
  }
  const char* key = j.contains("crossings") ? "crossings" : "points";
  if (!j.contains(key) || !j[key].is_array())
    throw scene::InputError(
        path +
        ": key 'crossings': expected an array of {mach, angle_deg, restitution, "
        "restitution_ci} (pipeline parametric writes one; pipeline calibrate's "
        "calibration.json has them as 'points')");
  Source s;
  for (const auto& c : j[key]) {
    auto num = [&](const char* k) {
      if (!c.contains(k) || !c[k].is_number())
        throw scene::InputError(path + ": key '" + key + "[]." + k + "': expected a number");
      return c[k].get<double>();
    };
    if (std::string(key) == "points" && (!c.contains("restitution") || c["restitution"].is_null()))
      continue;  // no crossing on this wedge
    const double gas = c.contains("gas_angle_deg") && c["gas_angle_deg"].is_number()
                           ? c["gas_angle_deg"].get<double>()
                           : scene::kNaN;
    s.crossings.push_back(crossing_entry(num("mach"), num("angle_deg"), num("restitution"),
                                         num("restitution_ci"), gas));
    if (!(s.crossings.back().restitution > 0 && s.crossings.back().restitution <= 1))
      throw scene::InputError(path + ": key '" + key + "[].restitution': outside (0, 1]");
  }
  const auto& cpu = j.contains("cpu_seconds") ? j["cpu_seconds"] : nlohmann::json();
  if (cpu.is_number())
    s.cpu_seconds = cpu.get<double>();
  else if (cpu.is_object() && cpu.contains("total") && cpu["total"].is_number())
    s.cpu_seconds = cpu["total"].get<double>();
  return s;
}

// What a join keeps of the table it extends (its first source): the local
// correction's widths and the angle scatter measured on unseen wedges.
struct Extended {
  CorrectionWidths widths;
  std::optional<AngleScatter> angle_scatter;
};

bool is_table_file(const std::string& path) {
  const auto ext = std::filesystem::path(path).extension().string();
  return ext == ".yaml" || ext == ".yml";
}

Extended extended_table(const std::string& path) {
  const auto t = is_table_file(path) ? read_calibration(path) : CalibrationTable{};
  if (!t.local_correction)
    throw scene::InputError(path +
                            ": key 'local_correction': --extend needs the first --from-points "
                            "file to be a table with a local correction");
  return {{t.local_correction->bandwidth_log_mach, t.local_correction->bandwidth_angle_deg},
          t.angle_scatter};
}

Source read_source(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw scene::InputError(path + ": --from-points file not found");
  return is_table_file(path) ? table_source(path) : json_source(path);
}
}  // namespace

nlohmann::json calibrate_from_points(const std::vector<std::string>& sources,
                                     const std::string& table_path, bool extend) {
  if (sources.empty()) throw scene::InputError("calibrate: --from-points needs at least one file");
  const auto kept = extend ? std::optional(extended_table(sources.front())) : std::nullopt;
  std::vector<std::string> origin;  // the source of each entry, to name a wedge given twice
  CalibrationTable table;
  int skipped = 0;
  double cpu = 0;
  for (const auto& path : sources) {
    const Source s = read_source(path);
    cpu += s.cpu_seconds;  // NaN when any source does not record it
    for (const auto& c : s.crossings) {
      if (is_case_study(c.mach, c.angle_deg)) {
        ++skipped;
        continue;
      }
      for (std::size_t k = 0; k < table.entries.size(); ++k)
        if (same_wedge({table.entries[k].mach, table.entries[k].angle_deg},
                       {c.mach, c.angle_deg})) {
          std::ostringstream m;
          m << path << ": the wedge M" << c.mach << " / " << c.angle_deg << " deg is also in "
            << origin[k] << ": each training wedge once";
          throw scene::InputError(m.str());
        }
      origin.push_back(path);
      table.entries.push_back(c);
    }
  }
  std::vector<RestitutionPoint> pts;
  for (const auto& c : table.entries)
    pts.push_back({c.mach, c.angle_deg, c.restitution, c.restitution_ci});
  std::string names;
  for (const auto& p : sources) names += (names.empty() ? "" : ", ") + p;
  const auto choice = choose_restitution_model(pts);
  if (!choice)
    throw scene::RunError(names + ": " + std::to_string(pts.size()) +
                          " usable crossing(s): too few, or all at one Mach number, to fit e(M)");
  table.model = choice->fit().model;
  table.fits = choice->candidates;
  const auto local =
      keep_local_correction(table, pts, kept ? std::optional(kept->widths) : std::nullopt);
  if (kept) table.angle_scatter = kept->angle_scatter;
  // What the crossings cost to measure, when every source records it.
  table.cpu_seconds = cpu;
  const std::string out = table_path.empty() ? builtin_calibration_path() : table_path;
  table.bow_shock = bow_shock_kept_by_wedge_fit(out);
  write_calibration(table, out);
  nlohmann::json r = {{"points", pts.size()},
                      {"case_studies_left_out", skipped},
                      {"model", model_formula(choice->fit().model)},
                      {"coefficients", choice->fit().coefficients},
                      {"residual_sd", choice->fit().residual_sd},
                      {"loo_rms", choice->fit().loo_rms},
                      {"table", out},
                      {"source", sources},
                      {"bow_shock_kept", table.bow_shock.has_value()},
                      {"angle_scatter_kept", table.angle_scatter.has_value()},
                      {"local_correction", local_correction_json(local)}};
  return r;
}

}  // namespace pipeline
