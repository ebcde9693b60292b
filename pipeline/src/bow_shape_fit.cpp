#include "pipeline/bow_shape_fit.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "cfd/history.hpp"
#include "json_fields.hpp"
#include "pipeline/restitution_crossing.hpp"
#include "pipeline/restitution_fit.hpp"
#include "pipeline/run.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace pipeline {

namespace {
using scene::kNaN;
// The crossing is where the granular standoff equals the gas's, on a line
// through the swept e this close to it (1.5 sweep steps: the standoff's
// curvature in e stays below the runs' scatter over that range).
constexpr double kSameStandoff = 1.0;
constexpr double kCrossingLineWindow = 0.0075;

std::string e_dir(const std::string& root, const std::string& body, const char* what, double e) {
  std::ostringstream d;
  d << root << "/" << body << "/" << what << e;
  return d.str();
}

// One sweep run's measure: granular standoff / gas standoff, and its 95%
// half-width (the granular standoff's interval over the gas standoff).
// (SweepPoint's `angle` holds the ratio; the crossing is at 1.)
// A run whose standoff is known to worse than this (relative 95% half-width)
// is a misfit, not a measure to cross a 5% target with.
constexpr double kMaxStandoffRelativeCi = 0.1;

SweepPoint standoff_ratio_point(double e, const nlohmann::json& granular_summary, double gas) {
  const double d = number_or_nan(granular_summary, "standoff");
  const double ci = number_or_nan(granular_summary, "standoff_ci");
  const bool ok = d > 0 && ci / d <= kMaxStandoffRelativeCi;  // NaN fails
  return {e, ok ? d / gas : kNaN, ci / gas};
}

struct Measured {
  nlohmann::json summary;
  double cpu = 0;
};
Measured run_at(const scene::Scene& base, double e, std::uint64_t seed, const std::string& dir,
                int np) {
  const scene::CpuStopwatch cpu;
  auto r = run_prediction_at(base, e, seed, dir, np);
  return {std::move(r), cpu.seconds()};
}

struct Crossed {
  BowShapePoint point;
  const BowTrainingRun* run = nullptr;
  double wedge_rms = kNaN;  // the body's station RMS at the wedge e(M), the baseline
};

// The sweep around the wedge e(M), then bisection of the bracket.
std::optional<Crossed> sweep_body(const BowTrainingRun& run, const CalibrationTable& t,
                                  const BowShapeOptions& o, double& cpu, nlohmann::json& report) {
  const scene::Scene& s = run.scene;
  const double gas = gas_standoff(run);
  const double e_wedge =
      interpolate_restitution(t, s.freestream.mach, kNaN).value_or(kMaxRestitution);
  std::vector<SweepPoint> pts;
  nlohmann::json sweep = nlohmann::json::array();
  const auto measure = [&](double e) {
    const auto runs = run_at_seeds(
        e, o.seeds, s.granular.seed, e_dir(o.cache_dir, s.name, "e", e), pts,
        [&](std::uint64_t seed, const std::string& dir) {
          const auto m = run_at(s, e, seed, dir, o.np);
          cpu += m.cpu;
          return std::pair{
              standoff_ratio_point(e, m.summary, gas),
              nlohmann::json{
                  {"seed", seed},
                  {"standoff", json_number(number_or_nan(m.summary, "standoff"))},
                  {"standoff_ci", json_number(number_or_nan(m.summary, "standoff_ci"))}}};
        });
    const SweepPoint& p = runs.mean;
    sweep.push_back({{"restitution", e},
                     {"runs", runs.records},
                     {"standoff_ratio", json_number(p.angle)},
                     {"standoff_ratio_ci", json_number(p.ci)}});
    scene::log_line("calibrate: " + s.name + " e = " + std::to_string(e) + ": standoff " +
                    std::to_string(p.angle * gas) + " (mean of " + std::to_string(o.seeds) +
                    " seeds) against the gas's " + std::to_string(gas));
  };
  for (const double off : o.offsets) {
    const double e = swept_restitution(e_wedge + off);
    if (std::none_of(pts.begin(), pts.end(), [e](const SweepPoint& p) { return p.e == e; }))
      measure(e);
  }
  for (int k = 0; k < o.refinements; ++k) {
    const auto next = next_restitution(pts, kSameStandoff);
    if (!next) break;
    measure(*next);
  }
  const auto c = find_crossing_by_line(pts, kSameStandoff, kCrossingLineWindow);
  report = {{"body", s.name},
            {"mach", s.freestream.mach},
            {"gas_standoff", gas},
            {"gas_shock", run.gas_csv},
            {"sweep", sweep},
            {"crossing", c ? nlohmann::json{{"restitution", c->e}, {"restitution_ci", c->e_ci}}
                           : nlohmann::json(nullptr)}};
  if (!c) return std::nullopt;
  BowShapePoint p;
  p.body = s.name;
  p.mach = s.freestream.mach;
  p.restitution = c->e;
  p.restitution_ci = c->e_ci;
  return Crossed{p, &run};
}

// The left-out e at fresh seeds, against the gas shock: the standoff's mean
// over the seeds, the stations' errors pooled over them.
void check_left_out(BowShapePoint& p, const BowTrainingRun& run, const BowShapeOptions& o,
                    double& cpu, nlohmann::json& report) {
  const double e = swept_restitution(p.loo_restitution);
  const std::string dir = e_dir(o.cache_dir, run.scene.name, "loo_e", e);
  const double gas = gas_standoff(run);
  double standoff = 0, ss = 0, sum = 0;
  std::size_t stations = 0;
  nlohmann::json seeds = nlohmann::json::array();
  for (int k = 0; k < o.seeds; ++k) {
    const std::uint64_t seed = nth_seed(run.scene.granular.seed + kLeaveOneOutSeedOffset, k);
    const std::string d = seed_dir(dir, k, seed);
    const auto m = run_at(run.scene, e, seed, d, o.np);
    cpu += m.cpu;
    const StationErrors st = station_errors(d + "/shockfit/shock.csv", run.gas_csv);
    const double n = static_cast<double>(st.relative.size());
    ss += st.rms * st.rms * n;
    sum += st.mean * n;
    stations += st.relative.size();
    const double standoff_k = number_or_nan(m.summary, "standoff");
    standoff += standoff_k / o.seeds;
    seeds.push_back({{"seed", seed},
                     {"standoff", json_number(standoff_k)},
                     {"standoff_relative_error", json_number(standoff_k / gas - 1.0)},
                     {"relative_rms", st.rms}});
  }
  const double n = static_cast<double>(stations);
  p.loo_mean = sum / n;
  p.loo_rms = std::sqrt(ss / n);
  p.loo_standoff = standoff / gas - 1.0;
  report["left_out"] = {
      {"restitution", e},          {"runs", seeds},
      {"stations", stations},      {"relative_mean", p.loo_mean},
      {"relative_rms", p.loo_rms}, {"standoff_relative_error", json_number(p.loo_standoff)}};
}
}  // namespace

double gas_standoff(const BowTrainingRun& r) {
  const scene::BodyGeometry g = scene::make_body(*r.scene.body);
  const double d = (g.nose.x - cfd::last_history_value(r.gas_case, "shock_x")) / g.length;
  if (!(d > 0))
    throw scene::InputError(r.gas_case +
                            "/history.csv: key 'shock_x': the gas shock is not ahead of the nose");
  return d;
}

StationErrors wedge_station_errors(const BowTrainingRun& run, const CalibrationTable& t,
                                   const BowShapeOptions& o) {
  if (o.cache_dir.empty())
    throw scene::InputError("calibrate: --fit-shapes needs --out (the granular runs' cache)");
  const double e = quantised_restitution(
      interpolate_restitution(t, run.scene.freestream.mach, kNaN).value_or(kMaxRestitution));
  if (ran_at_table_restitution(run.scene, t))
    return run_station_errors(run.run_dir);  // the run itself is at the wedge e(M)
  const std::string dir = e_dir(o.cache_dir, run.scene.name, "wedge_e", e);
  const auto m = run_at(run.scene, e, run.scene.granular.seed, dir, o.np);
  StationErrors st = station_errors(dir + "/shockfit/shock.csv", run.gas_csv);
  st.body = run.scene.name;
  st.mach = run.scene.freestream.mach;
  st.cpu_seconds = m.cpu + run.grid_cpu_seconds;
  st.shape = scene::bow_shape_class(*run.scene.body).value_or("");
  st.standoff_relative = standoff_relative_error(dir + "/shockfit/summary.json", run);
  return st;
}

std::optional<BowShapeFit> fit_bow_shape(const std::string& shape,
                                         const std::vector<BowShapePoint>& points) {
  if (points.size() <= kBowShapeCoefficients) return std::nullopt;
  std::vector<RestitutionPoint> rp;
  for (const auto& p : points) rp.push_back({p.mach, 0.0, p.restitution, p.restitution_ci});
  const auto fit = fit_restitution(rp, RestitutionModel::inverse_mach2);
  if (!fit) return std::nullopt;
  BowShapeFit f;
  f.shape = shape;
  f.coefficients = fit->coefficients;
  f.points = points;
  for (std::size_t i = 0; i < rp.size(); ++i) {
    const auto loo = leave_one_out_restitution(rp, RestitutionModel::inverse_mach2, i);
    if (!loo) return std::nullopt;
    f.points[i].loo_restitution = std::min(*loo, kMaxRestitution);
  }
  return f;
}

BowShapeResult fit_bow_shapes(const std::vector<BowTrainingRun>& runs,
                              const std::vector<StationErrors>& wedge_errors,
                              const CalibrationTable& t, const BowShapeOptions& o) {
  if (o.cache_dir.empty())
    throw scene::InputError("calibrate: --fit-shapes needs --out (the granular runs' cache)");
  BowShapeResult out;
  out.report = nlohmann::json::array();
  // Said before it starts: the sweeps are minutes to an hour, not seconds.
  const std::size_t per_body = (o.offsets.size() + static_cast<std::size_t>(o.refinements) + 1) *
                               static_cast<std::size_t>(o.seeds);
  scene::log_line("calibrate: fitting blunt shapes on " + std::to_string(runs.size()) +
                      " bodies: up to " + std::to_string(per_body * runs.size()) +
                      " granular runs (10-60 CPU s each at the default granular scale; cached "
                      "under " +
                      o.cache_dir + ", so a rerun resumes)",
                  true);
  std::map<std::string, std::vector<Crossed>> by_shape;
  std::map<std::string, nlohmann::json> body_report;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const BowTrainingRun& run = runs[k];
    const auto shape = scene::bow_shape_class(*run.scene.body);
    nlohmann::json r;
    if (!shape) {
      out.report.push_back({{"body", run.scene.name},
                            {"shape", nullptr},
                            {"note", "no shape class (polygons keep the wedge e(M))"}});
      continue;
    }
    if (auto c = sweep_body(run, t, o, out.cpu_seconds, r)) {
      c->wedge_rms = wedge_errors.at(k).rms;
      by_shape[*shape].push_back(*c);
    }
    r["shape"] = *shape;
    body_report[run.scene.name] = r;
  }
  for (auto& [shape, crossed] : by_shape) {
    std::vector<BowShapePoint> pts;
    for (const auto& c : crossed) pts.push_back(c.point);
    auto fit = fit_bow_shape(shape, pts);
    if (!fit) {
      for (const auto& c : crossed)
        body_report[c.point.body]["note"] =
            "no fit for the " + shape +
            " shape: fewer than 3 bodies crossed, or all at one Mach number";
      continue;
    }
    double ss = 0, ss_wedge = 0;
    for (std::size_t i = 0; i < fit->points.size(); ++i) {
      check_left_out(fit->points[i], *crossed[i].run, o, out.cpu_seconds,
                     body_report[fit->points[i].body]);
      ss += fit->points[i].loo_rms * fit->points[i].loo_rms;
      ss_wedge += crossed[i].wedge_rms * crossed[i].wedge_rms;
    }
    const double n = static_cast<double>(fit->points.size());
    fit->relative_rms = std::sqrt(ss / n);
    // Like any model, a shape's own e(M) must beat the baseline out of
    // sample: the wedge e(M) on the same bodies (their training runs).
    const double baseline = std::sqrt(ss_wedge / n);
    const bool pays = fit->relative_rms < baseline;
    out.shapes.push_back({{"shape", shape},
                          {"coefficients", fit->coefficients},
                          {"left_out_relative_rms", fit->relative_rms},
                          {"wedge_e_relative_rms", baseline},
                          {"used", pays}});
    if (pays) out.fits.push_back(*fit);
  }
  for (auto& [name, r] : body_report) out.report.push_back(r);
  return out;
}

}  // namespace pipeline
