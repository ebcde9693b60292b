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
  v.case_name = r.value("case", "");
  return v;
}

// The recorded runs whose family name passes `keep`.
template <typename Keep>
std::vector<VerdictRun> runs_where(const nlohmann::json& summary, const std::string& path, Keep keep) {
  if (!summary.contains("runs") || !summary["runs"].is_array())
    throw scene::InputError(path + ": key 'runs' missing (not a `pipeline run` summary)");
  std::vector<VerdictRun> out;
  for (std::size_t k = 0; k < summary["runs"].size(); ++k)
    if (keep(summary["runs"][k].value("family", "")))
      out.push_back(verdict_run(summary["runs"][k], path + ": runs[" + std::to_string(k) + "]"));
  return out;
}

struct RecordedRuns {
  std::vector<VerdictRun> clustered, uniform;
  PrimaryError primary;
  double predictor_cpu = 0;
};

RecordedRuns recorded_runs(const nlohmann::json& s, const std::string& path) {
  RecordedRuns rec;
  rec.uniform = runs_where(s, path, [](const std::string& f) { return f == "uniform"; });
  rec.clustered = runs_where(s, path, [](const std::string& f) { return f.rfind("clustered", 0) == 0; });
  const nlohmann::json details = s.value("verdict_details", nlohmann::json::object());
  rec.primary.name = s.value("primary_error", details.value("primary_error", ""));
  rec.primary.reference = details.value("primary_error_reference", "");
  if (rec.primary.name.empty()) throw scene::InputError(path + ": key 'primary_error' missing");
  rec.predictor_cpu = number_or_nan(details, "predictor_cpu_seconds");
  if (!std::isfinite(rec.predictor_cpu))
    throw scene::InputError(path + ": key 'verdict_details.predictor_cpu_seconds' missing");
  return rec;
}

// Each grid's primary error measured again from its case.
void remeasure(const scene::Scene& s, const std::string& run_dir, const PrimaryError& primary,
               std::vector<VerdictRun>& runs, nlohmann::json& errors) {
  for (auto& r : runs) {
    const std::string name = r.case_name.empty() ? level_name(r.family, r.level) : r.case_name;
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

}  // namespace

nlohmann::json read_run_summary(const std::string& path, const std::string& when_missing) {
  if (!std::filesystem::is_regular_file(path)) throw scene::InputError(path + ": " + when_missing);
  try {
    return nlohmann::json::parse(scene::read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw scene::InputError(path + ": not JSON (" + e.what() + ")");
  }
}

std::vector<VerdictRun> recorded_family(const nlohmann::json& summary, const std::string& path,
                                        const std::string& family) {
  return runs_where(summary, path, [&](const std::string& f) { return f == family; });
}

Verdict rejudge_summary(const std::string& summary_path) {
  const RecordedRuns rec = recorded_runs(read_run_summary(summary_path, kNoRunSummary), summary_path);
  return make_verdict(rec.primary, rec.clustered, rec.uniform, rec.predictor_cpu);
}

std::string write_rejudged(const std::string& run_dir, bool remeasure_errors) {
  const std::string path = run_dir + "/summary.json";
  const nlohmann::json summary = read_run_summary(path, kNoRunSummary);
  RecordedRuns rec = recorded_runs(summary, path);
  nlohmann::json errors = nlohmann::json::object();
  if (remeasure_errors) {
    // The primary error a new run of the resolved scene would choose.
    const scene::Scene s = scene::load_scene(run_dir + "/scene.resolved.yaml");
    rec.primary = primary_error_for(s);
    remeasure(s, run_dir, rec.primary, rec.uniform, errors);
    remeasure(s, run_dir, rec.primary, rec.clustered, errors);
  }
  const Verdict v = make_verdict(rec.primary, rec.clustered, rec.uniform, rec.predictor_cpu);
  nlohmann::json j;
  j["scene"] = summary.value("scene", "");
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
