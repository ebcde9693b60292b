#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <optional>
#include <sstream>

#include "json_fields.hpp"
#include "pipeline/calibration.hpp"
#include "pipeline/calibration_report.hpp"
#include "pipeline/calibration_training.hpp"
#include "pipeline/plot.hpp"
#include "pipeline/restitution_crossing.hpp"
#include "pipeline/restitution_fit.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/body_traits.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
using scene::kDeg;
using scene::kNaN;
// The calibration target: the ideal diatomic gas of the CFD.
constexpr double kTargetGamma = 1.4;

// Case-study checks use the scene's seed plus this offset (the left-out
// checks use kLeaveOneOutSeedOffset): the two checks see different replicas.
constexpr std::uint64_t kCaseStudySeedOffset = 2000;
// The crossing is read off a parabola through the swept e this close to it:
// the bracket and one run on either side at the refinements' spacing
// (0.005), never the run at e = 1 where angle(e) turns up too sharply for a
// parabola (M2.5/14: 37.2 deg at 0.99, 47.2 at 1) unless the crossing lies
// within 0.0105 of it.
constexpr double kCrossingCurveWindow = 0.0105;
// e is rounded like `pipeline run` rounds the table's value, so a case study
// here runs at the e the pipeline would use.
double rounded_restitution(double e) {
  return std::min(kMaxRestitution, quantised_restitution(e));
}

double gas_angle_deg(const scene::Scene& s, const std::string& origin) {
  const auto beta =
      scene::oblique_shock_beta(s.freestream.mach, s.body->angle_deg * kDeg, kTargetGamma);
  if (!beta)
    throw scene::InputError(
        origin +
        ": key 'body.angle_deg': detached at gamma 1.4; no shock angle to calibrate against");
  return *beta / kDeg;
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// One granular + shockfit run at e and seed; the granular angle, its 95%
// interval and the CPU seconds it cost: its stages' own, recorded when they
// ran, so that a cached run (a resumed calibration) counts what it cost
// then; this process's CPU where the stages predate that record.
struct Measured {
  double angle = kNaN, ci = kNaN, cpu = 0;
};
Measured measure(const scene::Scene& base, double e, std::uint64_t seed, const std::string& dir,
                 int np) {
  const double c0 = cpu_seconds();
  const auto r = run_prediction_at(base, e, seed, dir, np);
  const double recorded = number_or_nan(r, "predictor_cpu_seconds");
  return {number_or_nan(r, "shock_angle_deg"), number_or_nan(r, "shock_angle_ci_deg"),
          std::isfinite(recorded) ? recorded : cpu_seconds() - c0};
}

std::string e_dir(const std::string& root, const std::string& name, const char* what, double e) {
  std::ostringstream d;
  d << root << "/" << name << "/" << what << e;
  return d.str();
}

void check_seed_room(const scene::Scene& s, const std::string& origin) {
  if (static_cast<std::uint64_t>(s.granular.replicas) >= kLeaveOneOutSeedOffset)
    throw scene::InputError(
        origin + ": key 'granular.replicas': calibrate needs fewer than " +
        std::to_string(kLeaveOneOutSeedOffset) +
        " replicas (the out-of-sample seeds start that far above granular.seed)");
}

struct Training {
  scene::Scene scene;
  std::string origin;
};

std::vector<Training> training_set(const CalibrateOptions& o,
                                   const std::vector<WedgePoint>& cases) {
  std::vector<Training> out;
  if (o.scenes.empty()) {
    for (const auto& p : training_wedges(o.machs, o.angles_deg, kTargetGamma, cases))
      out.push_back({training_scene(p, o.averaging.value_or(default_training_averaging())),
                     "calibrate training wedge"});
    if (out.empty())
      throw scene::InputError(
          "calibrate: --mach x --angle gives no attached wedge outside the case studies");
  } else {
    if (o.averaging)
      throw scene::InputError(
          "calibrate: --averaging sets generated training wedges; with --scene set "
          "granular.averaging in each scene");
    for (const auto& path : o.scenes) {
      scene::Scene s = scene::load_scene(path);
      if (!s.body || !scene::calibration_angle_deg(*s.body))
        throw scene::InputError(path + ": key 'body.kind': calibrate needs wedge scenes");
      out.push_back({s, path});
    }
  }
  for (const auto& t : out) {
    gas_angle_deg(t.scene, t.origin);  // a detached wedge fails before any run
    check_seed_room(t.scene, t.origin);
  }
  return out;
}
}  // namespace

nlohmann::json run_calibration(const CalibrateOptions& o) {
  const auto t_wall = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  if (o.restitutions.size() < 2)
    throw scene::InputError("calibrate: --e needs at least two values");
  if (o.refinements < 0) throw scene::InputError("calibrate: --refine must be 0 or more");
  if (o.seeds < 1 || o.seeds > kMaxSweepSeeds)
    throw scene::InputError("calibrate: --seeds must lie in 1.." + std::to_string(kMaxSweepSeeds));
  for (const double e : o.restitutions)
    if (!(e > 0 && e <= 1)) throw scene::InputError("calibrate: --e values must lie in (0, 1]");
  std::vector<std::string> case_paths;
  for (const auto& p : case_study_scenes())
    if (fs::path(p).filename().string().rfind("wedge", 0) == 0) case_paths.push_back(p);
  std::vector<scene::Scene> cases;
  for (const auto& p : case_paths) cases.push_back(scene::load_scene(p));
  const auto case_points = wedge_points(case_paths);
  const auto training = training_set(o, case_points);

  const std::string table_path = o.table_path.empty() ? builtin_calibration_path() : o.table_path;
  // Read before any run, so a malformed table stops the calibration before it
  // costs anything.
  const auto bow_shock = bow_shock_kept_by_wedge_fit(table_path);
  scene::make_dirs(o.out_dir);
  const std::size_t n_runs =
      training.size() * ((o.restitutions.size() + static_cast<std::size_t>(o.refinements)) *
                             static_cast<std::size_t>(o.seeds) +
                         (o.verify ? 1 : 0)) +
      (o.verify ? cases.size() : 0);  // refinements may stop early: an upper bound
  scene::Progress progress("calibrate", static_cast<double>(n_runs), "runs");
  int done = 0;

  // 1. Sweep e on every training wedge and find the crossing.
  PlotSpec plot{"Granular shock angle against restitution (dashed: ideal-gas angle)",
                "restitution e",
                "shock angle (deg)",
                false,
                false,
                {},
                {}};
  nlohmann::json rows = nlohmann::json::array();
  std::vector<RestitutionPoint> points;
  std::vector<std::size_t> point_row;  // rows index of each point
  CalibrationTable table;
  table.gamma = kTargetGamma;
  double sweep_cpu = 0;
  for (const auto& t : training) {
    const scene::Scene& base = t.scene;
    const double mach = base.freestream.mach, theta = base.body->angle_deg;
    const double gas = gas_angle_deg(base, t.origin);
    std::vector<SweepPoint> pts;
    nlohmann::json sweep = nlohmann::json::array();
    // One e at every seed: the runs' mean is the sweep's point.
    const auto measure_all = [&](double e, int refinement) {
      const auto runs =
          run_at_seeds(e, o.seeds, base.granular.seed, e_dir(o.out_dir, base.name, "e", e), pts,
                       [&](std::uint64_t seed, const std::string& dir) {
                         const auto m = measure(base, e, seed, dir, o.np);
                         sweep_cpu += m.cpu;
                         progress.update(++done, base.name + " e=" + std::to_string(e));
                         return std::pair{SweepPoint{e, m.angle, m.ci},
                                          nlohmann::json{{"seed", seed},
                                                         {"shock_angle_deg", json_number(m.angle)},
                                                         {"ci_deg", json_number(m.ci)},
                                                         {"cpu_seconds", m.cpu}}};
                       });
      nlohmann::json row = {{"restitution", e},
                            {"shock_angle_deg", json_number(runs.mean.angle)},
                            {"ci_deg", json_number(runs.mean.ci)},
                            {"runs", runs.records}};
      if (refinement > 0) row["refinement"] = refinement;
      sweep.push_back(row);
    };
    for (const double e : o.restitutions) measure_all(e, 0);
    for (int r = 0; r < o.refinements; ++r) {  // sharpen the crossing (see next_restitution)
      const auto e = next_restitution(pts, gas);
      if (!e) break;
      measure_all(*e, r + 1);
    }
    nlohmann::json row = {{"scene", base.name},         {"mach", mach},
                          {"angle_deg", theta},         {"gas_angle_deg", gas},
                          {"seed", base.granular.seed}, {"sweep", sweep}};
    if (const auto cross = find_crossing_by_curve(pts, gas, kCrossingCurveWindow)) {
      const double e = cross->e, e_ci = cross->e_ci;
      row["restitution"] = e;
      row["restitution_ci"] = e_ci;
      row["on_step"] = crossing_on_step(pts, gas);
      point_row.push_back(rows.size());
      points.push_back({mach, theta, e, e_ci});
      table.entries.push_back(crossing_entry(mach, theta, e, e_ci, gas));
    } else {
      row["restitution"] = nullptr;
      row["note"] = "the granular angle does not cross the gas angle over the swept e";
    }
    rows.push_back(row);
    Series ser;
    ser.title = base.name;
    for (const auto& p : pts) {
      if (!usable(p)) continue;  // failed fits stay in calibration.json, not on the plot
      ser.x.push_back(p.e);
      ser.y.push_back(p.angle);
      ser.yerr.push_back(p.ci);
    }
    plot.series.push_back(ser);
    std::ostringstream hl;
    hl << "set arrow from " << pts.front().e << "," << gas << " to " << pts.back().e << "," << gas
       << " nohead dt 2 lw 1.5";
    plot.extra.push_back(hl.str());
  }

  // 2. Fit the smooth models and choose one by its leave-one-out error.
  const auto choice = choose_restitution_model(points);
  if (!choice)
    throw scene::RunError("calibrate: " + std::to_string(points.size()) +
                          " crossing(s) found; too few (or all at one Mach number) to fit e(M)");
  const RestitutionFit& fit = choice->fit();
  table.model = fit.model;
  table.fits = choice->candidates;
  const auto local = keep_local_correction(table, points);
  if (uses_angle(fit.model) && !table.fit(RestitutionModel::inverse_mach2))
    throw scene::RunError(
        "calibrate: the Mach-only model could not be fitted; blunt bodies would have no e");

  // 3. Out of sample: every training wedge at its leave-one-out e, then the
  // wedge case studies at the fitted e, each with a seed the fit never used.
  nlohmann::json case_rows = nlohmann::json::array();
  double check_cpu = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto e_loo = local ? leave_one_out_corrected(points, fit.model, local->bandwidth_log_mach,
                                                       local->bandwidth_angle_deg, i)
                             : leave_one_out_restitution(points, fit.model, i);
    auto& row = rows[point_row[i]];
    CalibrationEntry& c = table.entries[i];
    if (!e_loo) {
      row["note"] = "the model cannot be refitted without this point";
      continue;
    }
    c.loo_restitution = rounded_restitution(*e_loo);
    row["loo_restitution"] = c.loo_restitution;
    if (!o.verify) continue;
    const scene::Scene& base = training[point_row[i]].scene;
    const std::uint64_t seed = base.granular.seed + kLeaveOneOutSeedOffset;
    const auto m = measure(base, c.loo_restitution, seed,
                           e_dir(o.out_dir, base.name, "loo_e", c.loo_restitution), o.np);
    c.granular_angle_deg = m.angle;
    c.granular_angle_ci_deg = m.ci;
    check_cpu += m.cpu;
    row["loo_seed"] = seed;
    row["loo_granular_angle_deg"] = m.angle;
    row["loo_granular_angle_ci_deg"] = m.ci;
    row["loo_angle_error_deg"] = m.angle - c.gas_angle_deg;
    row["loo_cpu_seconds"] = m.cpu;
    progress.update(++done, base.name + " leave-one-out");
  }
  if (o.verify) {
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const scene::Scene& base = cases[k];
      const WedgePoint p = case_points[k];
      const double e = rounded_restitution(*interpolate_restitution(table, p.mach, p.angle_deg));
      const std::uint64_t seed = base.granular.seed + kCaseStudySeedOffset;
      const double gas = gas_angle_deg(base, case_paths[k]);
      const auto m =
          measure(base, e, seed, e_dir(o.out_dir, "case_studies/" + base.name, "e", e), o.np);
      check_cpu += m.cpu;
      bool in_sample = false;
      for (const auto& q : points) in_sample = in_sample || same_wedge(p, {q.mach, q.angle_deg});
      case_rows.push_back({{"scene", base.name},
                           {"mach", p.mach},
                           {"angle_deg", p.angle_deg},
                           {"restitution", e},
                           {"seed", seed},
                           {"gas_angle_deg", gas},
                           {"granular_angle_deg", m.angle},
                           {"granular_angle_ci_deg", m.ci},
                           {"angle_error_deg", m.angle - gas},
                           {"in_sample", in_sample},
                           {"cpu_seconds", m.cpu}});
      progress.update(++done, base.name + " at the fitted e");
    }
  }
  progress.finish();

  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& f : choice->candidates)
    candidates.push_back({{"model", model_key(f.model)},
                          {"formula", model_formula(f.model)},
                          {"coefficients", f.coefficients},
                          {"residual_sd", f.residual_sd},
                          {"loo_rms", f.loo_rms}});
  nlohmann::json out = {
      {"target_gamma", kTargetGamma},
      {"restitutions", o.restitutions},
      {"refinements", o.refinements},
      {"seeds", o.seeds},
      {"training_averaging",
       o.scenes.empty() ? nlohmann::json(o.averaging.value_or(default_training_averaging()))
                        : nlohmann::json(nullptr)},
      {"crossing_window", kCrossingCurveWindow},
      {"training", o.scenes.empty()
                       ? nlohmann::json{{"machs", o.machs}, {"angles_deg", o.angles_deg}}
                       : nlohmann::json{{"scenes", o.scenes}}},
      {"points", rows},
      {"model", model_key(fit.model)},
      {"candidates", candidates},
      {"local_correction", local_correction_json(local)},
      {"case_studies", case_rows},
      {"bow_shock_kept", bow_shock.has_value()},
      {"seed_offsets",
       {{"leave_one_out", kLeaveOneOutSeedOffset}, {"case_studies", kCaseStudySeedOffset}}},
      {"cpu_seconds",
       {{"sweeps", sweep_cpu},
        {"out_of_sample", check_cpu},
        {"total", sweep_cpu + check_cpu},
        {"this_process", cpu_seconds() - cpu0}}},
      {"wall_seconds",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - t_wall).count()}};
  out["summary"] = out_of_sample_summary(out);

  plot_png(plot, o.out_dir + "/calibration.png");
  // What the table cost: every run it used, cached ones at what they cost
  // when made (this process's own CPU is only the part it did not find).
  table.cpu_seconds = sweep_cpu + check_cpu;
  table.bow_shock = bow_shock;
  write_calibration(table, table_path);
  scene::write_json_atomic(o.out_dir + "/calibration.json", out);
  scene::write_file_atomic(
      o.markdown_path.empty() ? o.out_dir + "/calibration.md" : o.markdown_path,
      calibration_markdown(out));
  return out;
}

}  // namespace pipeline
