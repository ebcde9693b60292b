// `pipeline calibrate --from-points FILE`: the e(M[, theta]) fit trained on
// crossings measured elsewhere (the `crossings` of `pipeline parametric`'s
// parametric_calibration.json), with no granular run. The table records
// where its points came from: a calibration holds only for the granular
// settings its points were measured with.
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "pipeline/calibration.hpp"
#include "pipeline/calibration_report.hpp"
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
  constexpr double kSame = 1e-9;
  const double cases[][2] = {{3, 10}, {4, 15}, {5, 20}};
  for (const auto& c : cases)
    if (std::abs(mach - c[0]) < kSame && std::abs(angle_deg - c[1]) < kSame) return true;
  return false;
}
}  // namespace

nlohmann::json calibrate_from_points(const std::string& points_path, const std::string& table_path) {
  if (!std::filesystem::is_regular_file(points_path))
    throw scene::InputError(points_path + ": --from-points file not found");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(scene::read_file(points_path));
  } catch (const nlohmann::json::exception& e) {
    throw scene::InputError(points_path + ": not JSON: " + e.what());
  }
  if (!j.contains("crossings") || !j["crossings"].is_array())
    throw scene::InputError(points_path + ": key 'crossings': expected an array of {mach, angle_deg, restitution, "
                                          "restitution_ci} (pipeline parametric writes one)");
  std::vector<RestitutionPoint> pts;
  CalibrationTable table;
  int skipped = 0;
  for (const auto& c : j["crossings"]) {
    auto num = [&](const char* k) {
      if (!c.contains(k) || !c[k].is_number())
        throw scene::InputError(points_path + ": key 'crossings[].'" + std::string(k) + ": expected a number");
      return c[k].get<double>();
    };
    const RestitutionPoint p{num("mach"), num("angle_deg"), num("restitution"), num("restitution_ci")};
    if (is_case_study(p.mach, p.angle_deg)) {
      ++skipped;
      continue;
    }
    if (!(p.restitution > 0 && p.restitution <= 1))
      throw scene::InputError(points_path + ": key 'crossings[].restitution': outside (0, 1]");
    pts.push_back(p);
    CalibrationEntry e;
    e.mach = p.mach;
    e.angle_deg = p.angle_deg;
    e.restitution = p.restitution;
    e.restitution_ci = p.restitution_ci;
    e.gas_angle_deg = e.granular_angle_deg = e.granular_angle_ci_deg = scene::kNaN;
    table.entries.push_back(e);
  }
  const auto choice = choose_restitution_model(pts);
  if (!choice)
    throw scene::RunError(points_path + ": " + std::to_string(pts.size()) +
                          " usable crossing(s): too few, or all at one Mach number, to fit e(M)");
  table.model = choice->fit().model;
  table.fits = choice->candidates;
  const auto local = keep_local_correction(table, pts);
  // What the crossings cost to measure, when the points file records it.
  table.cpu_seconds = j.contains("cpu_seconds") && j["cpu_seconds"].is_number() ? j["cpu_seconds"].get<double>()
                                                                                 : std::nan("");
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
                      {"source", points_path},
                      {"bow_shock_kept", table.bow_shock.has_value()},
                      {"local_correction", local_correction_json(local)}};
  return r;
}

}  // namespace pipeline
