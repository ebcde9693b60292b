#include "pipeline/bow_shock_scatter.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "json_fields.hpp"
#include "pipeline/bow_shape_fit.hpp"
#include "pipeline/bow_station_bias.hpp"
#include "pipeline/grid_runs.hpp"
#include "pipeline/rejudge.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scene/shock_csv.hpp"

namespace pipeline {

namespace {
using scene::kNaN;

// Station surface points of one layout agree to round-off (12 digits written).
constexpr double kSameStation = 1e-9;
// Fewer common stations than this say nothing about a shock's shape.
constexpr std::size_t kMinStations = 3;

bool same_point(scene::Vec2 a, scene::Vec2 b) {
  if (!std::isfinite(a.x) || !std::isfinite(b.x)) return true;  // a file without surface columns
  return std::abs(a.x - b.x) <= kSameStation && std::abs(a.y - b.y) <= kSameStation;
}

// The scatter belongs to the table's e(M): a run made with another
// restitution (its own, or an older table's) measures something else.
// (The wedge e(M), not a shape's own fit: the pooled scatter is what a body
// without a shape fit gets from it.)
void check_table_restitution(const std::string& run_dir, const CalibrationTable& t,
                             const std::string& table_path) {
  const scene::Scene ran = scene::load_scene(run_dir + "/scene.resolved.yaml");
  const double e = interpolate_restitution(t, ran.freestream.mach, kNaN).value_or(kNaN);
  if (!ran_at_table_restitution(ran, t))
    throw scene::InputError(run_dir + "/scene.resolved.yaml: key 'granular.restitution': " +
                            std::to_string(ran.granular.restitution) + " is not the table's e(M) " +
                            std::to_string(e) + " (" + table_path +
                            "); rerun the body with that table and no restitution of its own");
}

void require_run_dir(const std::string& dir) {
  if (!std::filesystem::is_directory(dir))
    throw scene::InputError(
        dir + ": --bow-shock-runs: no such directory (a finished `pipeline run` expected)");
}

// A run's stations against its gas shock, refused unless it ran at the
// table's blunt law (what the pooled scatter and a station bias belong to).
StationErrors law_station_errors(const std::string& dir, const CalibrationTable& t,
                                 const std::string& table_path) {
  check_table_restitution(dir, t, table_path);
  return run_station_errors(dir);
}

// Per shape class without its own e fit, the fold of its bodies' stations
// (bow_station_bias.hpp); kept where it beats the uncorrected stations out of
// sample. A shape with an own e runs its bodies elsewhere than at the law.
nlohmann::json fit_station_biases(const std::vector<StationErrors>& bodies, BowShockScatter& w) {
  std::map<std::string, std::vector<StationErrors>> by_shape;
  for (const auto& b : bodies)
    if (!b.shape.empty() && !w.shape(b.shape)) by_shape[b.shape].push_back(b);
  nlohmann::json report = nlohmann::json::array();
  for (const auto& [shape, members] : by_shape) {
    const auto fit = fit_station_bias(shape, members);
    if (!fit) {
      report.push_back({{"shape", shape},
                        {"runs", members.size()},
                        {"used", false},
                        {"note", "no fit: fewer than " + std::to_string(kMinBiasBodies) +
                                     " bodies, a body without station normals or standoff, "
                                     "or a fold that would turn a distance negative"}});
      continue;
    }
    const bool pays = fit->relative_rms < fit->uncorrected_rms;
    nlohmann::json per_body = nlohmann::json::array();
    for (const auto& b : fit->bodies)
      per_body.push_back({{"body", b.body},
                          {"mach", b.mach},
                          {"relative_rms", b.rms},
                          {"standoff_relative_error", b.standoff},
                          {"left_out_relative_rms", b.loo_rms},
                          {"left_out_standoff_relative_error", b.loo_standoff}});
    nlohmann::json standoff_candidates = nlohmann::json::object();
    for (const auto& [name, rms] : fit->standoff_left_out_rms) standoff_candidates[name] = rms;
    report.push_back({{"shape", shape},
                      {"model", fit->model},
                      {"coefficients", fit->coefficients},
                      {"left_out_relative_rms", fit->relative_rms},
                      {"uncorrected_relative_rms", fit->uncorrected_rms},
                      {"standoff_model", fit->standoff_model},
                      {"standoff_coefficients", fit->standoff_coefficients},
                      {"standoff_left_out_rms", standoff_candidates},
                      {"used", pays},
                      {"bodies", per_body}});
    if (pays) w.station_biases.push_back(*fit);
  }
  return report;
}
}  // namespace

bool ran_at_table_restitution(const scene::Scene& ran, const CalibrationTable& t) {
  const double e = interpolate_restitution(t, ran.freestream.mach, kNaN).value_or(kNaN);
  return is_applied_restitution(ran.granular.restitution, e);
}

StationErrors station_errors(const std::string& granular_csv, const std::string& gas_csv) {
  const auto g = scene::read_shock_csv(granular_csv).rows;
  const auto c = scene::read_shock_csv(gas_csv).rows;
  StationErrors out;
  for (std::size_t i = 0; i < std::min(g.size(), c.size()); ++i) {
    if (!same_point(g[i].surface, c[i].surface))
      throw scene::InputError(granular_csv + " and " + gas_csv + ": station " + std::to_string(i) +
                              " is at another surface point (not the same body's stations)");
    if (!g[i].accepted || !c[i].accepted || !(c[i].distance > 0) || !std::isfinite(g[i].distance))
      continue;
    const double r = (g[i].distance - c[i].distance) / c[i].distance;
    out.relative.push_back(r);
    out.inclination_deg.push_back(inclination_deg(g[i].normal));
  }
  if (out.relative.size() < kMinStations)
    throw scene::InputError(
        granular_csv + " and " + gas_csv + ": " + std::to_string(out.relative.size()) +
        " stations accepted in both (at least " + std::to_string(kMinStations) + " needed)");
  set_mean_and_rms(out);
  return out;
}

void set_mean_and_rms(StationErrors& e) {
  double ss = 0, sum = 0;
  for (const double r : e.relative) {
    ss += r * r;
    sum += r;
  }
  const double n = static_cast<double>(e.relative.size());
  e.rms = std::sqrt(ss / n);
  e.mean = sum / n;
}

BowTrainingRun bow_training_run(const std::string& run_dir) {
  const std::string summary_path = run_dir + "/summary.json";
  const nlohmann::json sum =
      read_run_summary(summary_path, "not found (not a finished `pipeline run`)");
  const scene::Scene s = scene::load_scene(run_dir + "/scene.resolved.yaml");
  if (!s.body || scene::calibration_angle_deg(*s.body))
    throw scene::InputError(run_dir +
                            ": key 'body.kind': a bow shock's training needs a blunt body");
  if (is_case_study(s))
    throw scene::InputError(run_dir + ": the case study " + s.name +
                            " is a prediction, never a training point");
  const auto pred = sum.value("prediction", nlohmann::json::object());
  if (pred.value("predictor", "") != "granular")
    throw scene::InputError(summary_path +
                            ": key 'prediction.predictor': the run's predictor is not granular");
  double finest = kNaN, grid_cpu = kNaN;
  std::string finest_case;
  for (const auto& r : sum.value("runs", nlohmann::json::array()))
    if (r.value("family", "") == "uniform" && r.value("steady_state_reached", false)) {
      const double level = number_or_nan(r, "level");
      if (!(finest <= level)) {
        finest = level;
        grid_cpu = number_or_nan(r, "cpu_seconds") + number_or_nan(r, "mesh_cpu_seconds");
        finest_case = r.value("case", level_name("uniform", level));
      }
    }
  if (!std::isfinite(finest))
    throw scene::InputError(summary_path + ": key 'runs': no uniform grid reached steady state");
  const std::string gas = run_dir + "/cfd/" + finest_case;
  return {s,       run_dir, gas + "/shockfit/shock.csv", gas, number_or_nan(pred, "cpu_seconds"),
          grid_cpu};
}

StationErrors run_station_errors(const std::string& run_dir) {
  const BowTrainingRun r = bow_training_run(run_dir);
  StationErrors e = station_errors(run_dir + "/shockfit/shock.csv", r.gas_csv);
  e.body = r.scene.name;
  e.mach = r.scene.freestream.mach;
  e.cpu_seconds = r.predictor_cpu_seconds + r.grid_cpu_seconds;
  e.shape = scene::bow_shape_class(*r.scene.body).value_or("");
  e.standoff_relative = standoff_relative_error(run_dir + "/shockfit/summary.json", r);
  return e;
}

double standoff_relative_error(const std::string& granular_summary, const BowTrainingRun& r) {
  const double d = number_or_nan(
      read_run_summary(granular_summary, "not found (shockfit's summary of the granular run)"),
      "standoff");
  return d / gas_standoff(r) - 1.0;
}

BowShockScatter pooled_scatter(const std::vector<StationErrors>& bodies) {
  BowShockScatter w;
  if (bodies.empty()) return w;
  double ss = 0;
  w.cpu_seconds = 0.0;
  for (const auto& b : bodies) {
    ss += b.rms * b.rms;
    w.cpu_seconds += b.cpu_seconds;
    w.bodies.push_back(b.body);
    w.machs.push_back(b.mach);
    w.stations += static_cast<int>(b.relative.size());
  }
  w.relative_rms = std::sqrt(ss / static_cast<double>(bodies.size()));
  return w;
}

nlohmann::json calibrate_bow_shocks(const std::vector<std::string>& run_dirs,
                                    const std::string& table_path, const BowShapeOptions* shapes) {
  const std::string path = table_path.empty() ? builtin_calibration_path() : table_path;
  CalibrationTable table =
      read_calibration(path);  // a missing or malformed table fails before anything
  std::vector<StationErrors> bodies;
  std::vector<BowTrainingRun> runs;
  nlohmann::json per_body = nlohmann::json::array();
  for (const auto& dir : run_dirs) {
    require_run_dir(dir);
    // A run made at its shape's own e (a table that has one) still holds the
    // gas shock; with the sweeps' cache its body is rerun at the wedge e(M)
    // when needed.
    if (shapes) {
      runs.push_back(bow_training_run(dir));
      bodies.push_back(wedge_station_errors(runs.back(), table, *shapes));
    } else {
      bodies.push_back(law_station_errors(dir, table, path));
    }
    const auto& b = bodies.back();
    per_body.push_back({{"body", b.body},
                        {"run", dir},
                        {"stations", b.relative.size()},
                        {"relative_rms", b.rms},
                        {"relative_mean", b.mean},
                        {"cpu_seconds", json_number(b.cpu_seconds)}});
  }
  if (bodies.size() < 2)
    throw scene::InputError(
        "calibrate: --bow-shock-runs needs at least two training runs (one body has no scatter)");
  BowShockScatter scatter = pooled_scatter(bodies);
  nlohmann::json shape_report = nlohmann::json::array();
  if (shapes) {
    const BowShapeResult fitted = fit_bow_shapes(runs, bodies, table, *shapes);
    scatter.shapes = fitted.fits;
    // A shape none of these runs holds keeps the fit its own bodies gave.
    if (table.bow_shock)
      for (const auto& old : table.bow_shock->shapes)
        if (std::none_of(runs.begin(), runs.end(), [&](const BowTrainingRun& r) {
              return scene::bow_shape_class(*r.scene.body) == old.shape;
            }))
          scatter.shapes.push_back(old);
    scatter.cpu_seconds += fitted.cpu_seconds;
    shape_report = {{"bodies", fitted.report}, {"fits", fitted.shapes}};
  }
  // A fold measured on bodies these runs do not hold stays, where its shape
  // still runs at the law.
  if (table.bow_shock)
    for (const auto& old : table.bow_shock->station_biases)
      if (!scatter.shape(old.shape) &&
          std::none_of(bodies.begin(), bodies.end(),
                       [&](const StationErrors& b) { return b.shape == old.shape; }))
        scatter.station_biases.push_back(old);
  // The law the bodies ran at travels with what was measured under it.
  if (const RestitutionFit* law = blunt_restitution_law(table)) scatter.restitution_law = *law;
  table.bow_shock = scatter;
  write_calibration(table, path);
  return {{"table", path},
          {"relative_rms", table.bow_shock->relative_rms},
          {"stations", table.bow_shock->stations},
          {"cpu_seconds", json_number(table.bow_shock->cpu_seconds)},
          {"bodies", per_body},
          {"shapes", shape_report}};
}

nlohmann::json calibrate_station_biases(const std::vector<std::string>& run_dirs,
                                        const std::string& table_path) {
  const std::string path = table_path.empty() ? builtin_calibration_path() : table_path;
  CalibrationTable table = read_calibration(path);
  if (!table.bow_shock || !table.bow_shock->restitution_law)
    throw scene::InputError(path +
                            ": key 'bow_shock.restitution_law': the table records no blunt law "
                            "for a station bias to belong to (run --bow-shock-runs first)");
  std::vector<StationErrors> bodies;
  for (const auto& dir : run_dirs) {
    require_run_dir(dir);
    bodies.push_back(law_station_errors(dir, table, path));
  }
  BowShockScatter w = *table.bow_shock;
  // A shape these runs hold is refitted from them alone.
  std::erase_if(w.station_biases, [&](const BowStationBias& b) {
    return std::any_of(bodies.begin(), bodies.end(),
                       [&](const StationErrors& e) { return e.shape == b.shape; });
  });
  const nlohmann::json report = fit_station_biases(bodies, w);
  table.bow_shock = w;
  write_calibration(table, path);
  return {{"table", path}, {"station_bias", report}};
}

}  // namespace pipeline
