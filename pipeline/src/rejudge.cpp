#include "pipeline/rejudge.hpp"
#include "scene/units.hpp"

#include <cmath>
#include <filesystem>

#include "json_fields.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/grid_runs.hpp"
#include "pipeline/report.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"

namespace pipeline {

namespace {

nlohmann::json read_summary(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw scene::InputError(path + ": no such run summary");
  try {
    return nlohmann::json::parse(scene::read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw scene::InputError(path + ": not JSON (" + e.what() + ")");
  }
}

double required_number(const nlohmann::json& j, const char* key, const std::string& where) {
  const double v = number_or_nan(j, key);
  if (!std::isfinite(v)) throw scene::InputError(where + ": key '" + key + "' missing or not a number");
  return v;
}

VerdictRun verdict_run(const nlohmann::json& r, const std::string& where) {
  VerdictRun v;
  v.family = r.value("family", "");
  v.level = required_number(r, "level", where);
  v.cells = static_cast<long>(required_number(r, "cells", where));
  v.steps = static_cast<long>(number_or_nan(r, "steps") > 0 ? r["steps"].get<double>() : 0.0);
  v.cfd_cpu = required_number(r, "cpu_seconds", where);
  v.mesh_cpu = required_number(r, "mesh_cpu_seconds", where);
  v.error = number_or_nan(r, "primary_error");
  v.error_ci = number_or_nan(r, "primary_error_ci");
  v.steady = r.value("steady_state_reached", false);
  return v;
}

}  // namespace

namespace {

struct RecordedRuns {
  std::vector<VerdictRun> clustered, uniform;
  PrimaryError primary;
  double predictor_cpu = 0;
};

RecordedRuns recorded_runs(const std::string& summary_path) {
  const nlohmann::json s = read_summary(summary_path);
  if (!s.contains("runs") || !s["runs"].is_array())
    throw scene::InputError(summary_path + ": key 'runs' missing (not a `pipeline run` summary)");
  std::vector<VerdictRun> clustered, uniform;
  for (std::size_t k = 0; k < s["runs"].size(); ++k) {
    const std::string where = summary_path + ": runs[" + std::to_string(k) + "]";
    const VerdictRun v = verdict_run(s["runs"][k], where);
    if (v.family == "uniform") uniform.push_back(v);
    else if (v.family.rfind("clustered", 0) == 0) clustered.push_back(v);
  }
  const nlohmann::json details = s.value("verdict_details", nlohmann::json::object());
  PrimaryError primary;
  primary.name = s.value("primary_error", details.value("primary_error", ""));
  primary.reference = details.value("primary_error_reference", "");
  if (primary.name.empty()) throw scene::InputError(summary_path + ": key 'primary_error' missing");
  const double predictor_cpu = number_or_nan(details, "predictor_cpu_seconds");
  if (!std::isfinite(predictor_cpu))
    throw scene::InputError(summary_path + ": key 'verdict_details.predictor_cpu_seconds' missing");
  return {clustered, uniform, primary, predictor_cpu};
}

// Each grid's primary error measured again from its case.
void remeasure(const scene::Scene& s, const std::string& run_dir, const PrimaryError& primary,
               std::vector<VerdictRun>& runs, nlohmann::json& errors) {
  for (auto& r : runs) {
    const std::string name = level_name(r.family, r.level);
    try {
      const MeasuredError m = measure_named(measure_case_errors(s, run_dir + "/cfd/" + name), primary.name);
      r.error = m.value;
      r.error_ci = std::isfinite(m.uncertainty) ? m.uncertainty : 0.0;
      errors[name] = {{"primary_error", r.error}, {"primary_error_ci", r.error_ci}};
    } catch (const std::exception& e) {
      r.error = scene::kNaN;
      errors[name] = {{"note", std::string("not measured: ") + e.what()}};
    }
  }
}

Verdict remeasured_verdict(const std::string& run_dir, nlohmann::json& errors) {
  RecordedRuns rec = recorded_runs(run_dir + "/summary.json");
  const scene::Scene s = scene::load_scene(run_dir + "/scene.resolved.yaml");
  const PrimaryError primary = primary_error_for(s);
  remeasure(s, run_dir, primary, rec.uniform, errors);
  remeasure(s, run_dir, primary, rec.clustered, errors);
  return make_verdict(primary, rec.clustered, rec.uniform, rec.predictor_cpu);
}

}  // namespace

std::vector<VerdictRun> recorded_family(const nlohmann::json& summary, const std::string& path,
                                        const std::string& family) {
  std::vector<VerdictRun> out;
  if (!summary.contains("runs") || !summary["runs"].is_array())
    throw scene::InputError(path + ": key 'runs' missing (not a `pipeline run` summary)");
  for (std::size_t k = 0; k < summary["runs"].size(); ++k)
    if (summary["runs"][k].value("family", "") == family)
      out.push_back(verdict_run(summary["runs"][k], path + ": runs[" + std::to_string(k) + "]"));
  return out;
}

Verdict rejudge_summary(const std::string& summary_path) {
  const RecordedRuns rec = recorded_runs(summary_path);
  return make_verdict(rec.primary, rec.clustered, rec.uniform, rec.predictor_cpu);
}

Verdict rejudge_remeasured(const std::string& run_dir) {
  nlohmann::json errors = nlohmann::json::object();
  return remeasured_verdict(run_dir, errors);
}

std::string write_rejudged(const std::string& run_dir, bool remeasure_errors) {
  const std::string path = run_dir + "/summary.json";
  nlohmann::json errors = nlohmann::json::object();
  const Verdict v = remeasure_errors ? remeasured_verdict(run_dir, errors) : rejudge_summary(path);
  nlohmann::json j;
  j["scene"] = read_summary(path).value("scene", "");
  j["primary_error"] = v.primary.name;
  j["speedup_cfd"] = interval_json(v.speedup_cfd);
  j["speedup_total"] = interval_json(v.speedup_total);
  j["verdict"] = v.verdict;
  j["verdict_details"] = verdict_json(v);
  if (remeasure_errors) j["remeasured_errors"] = errors;
  const std::string line = verdict_line(j);
  j["verdict_line"] = line;
  scene::write_json_atomic(run_dir + "/verdict.json", j);
  return line;
}

}  // namespace pipeline
