// `pipeline parametric`: sizes the grid to the CPU budget, runs every point
// (granular + shockfit, one cached directory per point, in child processes)
// and gathers the rows.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "pipeline/parametric.hpp"
#include "pipeline/process_pool.hpp"
#include "pipeline/run.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {

namespace fs = std::filesystem;
using scene::kDeg;
using scene::kNaN;
// The granular gas's own ratio of specific heats: dilute hard disks, (d+2)/d in 2D.
constexpr double kGammaDisks = 2.0;
constexpr double kGammaAir = 1.4;
// Reference sizes of the cost model (a probe at another size is scaled).
constexpr double kRefParticles = 3000;
constexpr double kRefRadius = 60;
constexpr double kRefPacking = 0.1;
constexpr double kWarmupFlowThroughs = 2;  // granular's detected warm-up, typically
// A shock angle whose 95% half-width exceeds this is a fit through noise
// (small systems near detachment): tabulated, but not compared or trained on.
constexpr double kMaxResolvedCiDeg = 10;

std::string point_dir(const std::string& out, const ParametricPoint& p) {
  return out + "/points/" + point_key(p);
}

bool done(const std::string& out, const ParametricPoint& p) {
  return fs::exists(point_dir(out, p) + "/prediction.json");
}

// CPU of a point relative to the reference point of its body kind: disks in
// the domain times the flow-through time in collision times (both grow with
// the body's size in diameters: N^1.5, or R^3 at fixed domain shape), times
// the collision rate (packing), times the flow-through times simulated.
double relative_cost(const ParametricPoint& p) {
  const double size = p.body == "wedge" ? std::pow(p.particles / kRefParticles, 1.5)
                                        : std::pow(p.radius_d / kRefRadius, 3);
  return size * (p.packing / kRefPacking) * (kWarmupFlowThroughs + p.averaging) /
         (kWarmupFlowThroughs + 2.0);
}

// Runs one point in this process; false (and failed.json) when it failed.
bool run_point(const ParametricPoint& p, const std::string& dir) {
  try {
    const auto r = run_prediction(point_scene(p), dir, 1);
    scene::write_json_atomic(dir + "/prediction.json", r);
    return true;
  } catch (const std::exception& e) {
    if (scene::interrupted()) return false;
    scene::make_dirs(dir);
    scene::write_json_atomic(dir + "/failed.json", {{"error", e.what()}});
    scene::log_line("parametric: " + point_key(p) + " failed: " + e.what(), true);
    return false;
  }
}

double num(const nlohmann::json& j, const char* k) {
  return j.contains(k) && j[k].is_number() ? j[k].get<double>() : kNaN;
}

double beta_deg(double mach, double theta_deg, double gamma) {
  const auto b = scene::oblique_shock_beta(mach, theta_deg * kDeg, gamma);
  return b ? *b / kDeg : kNaN;
}

nlohmann::json row_of(const ParametricPoint& p, const std::vector<std::string>& panels,
                      const std::string& out, const std::string& status_if_missing) {
  nlohmann::json r{{"key", point_key(p)},
                   {"body", p.body},
                   {"mach", p.mach},
                   {"granular_mach", p.granular_mach},
                   {"restitution", p.restitution},
                   {"packing", p.packing},
                   {"averaging", p.averaging},
                   {"panels", panels}};
  if (p.body == "wedge") {
    r["theta_deg"] = p.theta_deg;
    r["particles"] = p.particles;
    r["gas_beta_deg"] = beta_deg(p.mach, p.theta_deg, kGammaAir);
    r["disk_gas_beta_deg"] = beta_deg(p.granular_mach, p.theta_deg, kGammaDisks);
    r["mach_angle_deg"] = std::asin(1.0 / p.granular_mach) / kDeg;
    r["max_deflection_deg"] = scene::max_deflection(p.mach, kGammaAir) / kDeg;
    r["disk_max_deflection_deg"] = scene::max_deflection(p.granular_mach, kGammaDisks) / kDeg;
  } else {
    r["radius_d"] = p.radius_d;
    r["billig_standoff"] = scene::billig_standoff_cylinder(p.mach);
  }
  r["case_study"] = is_case_study(p);
  const std::string dir = point_dir(out, p);
  nlohmann::json pred = nlohmann::json::object();
  if (fs::exists(dir + "/prediction.json")) {
    pred = nlohmann::json::parse(scene::read_file(dir + "/prediction.json"));
    r["status"] = "ok";
  } else {
    r["status"] = fs::exists(dir + "/failed.json") ? "failed" : status_if_missing;
  }
  r["shock"] = pred.value("shock", "");
  r["beta_deg"] = num(pred, "shock_angle_deg");
  r["beta_ci_deg"] = num(pred, "shock_angle_ci_deg");
  r["standoff"] = num(pred, "standoff");
  r["standoff_ci"] = num(pred, "standoff_ci");
  r["cpu_seconds"] = num(pred, "predictor_cpu_seconds");
  // Resolved: a shock angle between the wall and the normal with a usable
  // interval, or a positive standoff with an interval.
  const double b = r["beta_deg"].get<double>(), bci = r["beta_ci_deg"].get<double>();
  const double s = r["standoff"].get<double>(), sci = r["standoff_ci"].get<double>();
  r["resolved"] = p.body == "wedge"
                      ? std::isfinite(b) && b > p.theta_deg && b < 90 && bci <= kMaxResolvedCiDeg
                      : std::isfinite(s) && s > 0 && std::isfinite(sci);
  // Training data for the e calibration: wedges whose granular stream is the
  // gas's Mach at the default packing, resolved, not a case study.
  r["calibration_training"] = p.body == "wedge" && !is_case_study(p) && p.granular_mach == p.mach &&
                              p.packing == kRefPacking && r["resolved"].get<bool>();
  return r;
}

}  // namespace

nlohmann::json run_parametric(const ParametricOptions& o) {
  if (o.out_dir.empty()) throw scene::InputError("--out: an output directory is required");
  if (!(o.budget_cpu_seconds > 0)) throw scene::InputError("--budget-cpu-seconds: must be > 0");
  if (o.jobs < 1) throw scene::InputError("--jobs: must be >= 1");
  const auto panels =
      o.panels.empty() ? parametric_panels(o.quick ? ParametricGrid::quick : ParametricGrid::full)
                       : o.panels;

  // Unique points, in panel order, with the panels each belongs to.
  std::vector<ParametricPoint> points;
  std::map<std::string, std::vector<std::string>> panels_of;
  for (const auto& panel : panels)
    for (const auto& p : panel.points) {
      auto& ids = panels_of[point_key(p)];
      if (ids.empty()) points.push_back(p);
      if (std::find(ids.begin(), ids.end(), panel.id) == ids.end()) ids.push_back(panel.id);
    }
  for (const auto& p : points) (void)point_scene(p);  // every scene valid before any run
  scene::make_dirs(o.out_dir + "/points");
  const scene::CpuStopwatch cpu;

  // CPU per reference point of each body kind: from points already done, or
  // from a first run (the probe) of one that is not.
  std::map<std::string, double> unit;
  std::map<std::string, int> unit_n;
  for (const auto& p : points)
    if (done(o.out_dir, p)) {
      const auto pred =
          nlohmann::json::parse(scene::read_file(point_dir(o.out_dir, p) + "/prediction.json"));
      const double c = num(pred, "predictor_cpu_seconds");
      if (std::isfinite(c)) {
        unit[p.body] += c / relative_cost(p);
        ++unit_n[p.body];
      }
    }
  for (auto& [kind, u] : unit) u /= unit_n[kind];
  int probes = 0;
  for (const std::string kind : {"wedge", "disc"}) {
    if (unit.count(kind) || scene::interrupted()) continue;
    const ParametricPoint* probe = nullptr;
    for (const auto& p : points)
      if (p.body == kind && !done(o.out_dir, p) &&
          (!probe || std::abs(relative_cost(p) - 1) < std::abs(relative_cost(*probe) - 1)))
        probe = &p;
    if (!probe) continue;
    scene::log_line("parametric: measuring CPU per " + kind + " point on " + point_key(*probe),
                    true);
    const scene::CpuStopwatch probe_cpu;
    run_point(*probe, point_dir(o.out_dir, *probe));
    ++probes;
    unit[kind] = probe_cpu.seconds() / relative_cost(*probe);
  }
  if (scene::interrupted())
    throw scene::RunError("interrupted while measuring the CPU per point; rerun to resume");

  // Estimate the rest; over budget, the most expensive points go first.
  std::vector<ParametricPoint> todo;
  for (const auto& p : points)
    if (!done(o.out_dir, p) && !fs::exists(point_dir(o.out_dir, p) + "/failed.json"))
      todo.push_back(p);
  auto estimate = [&](const ParametricPoint& p) { return unit[p.body] * relative_cost(p); };
  std::stable_sort(todo.begin(), todo.end(),
                   [&](const auto& a, const auto& b) { return estimate(a) < estimate(b); });
  double total = 0;
  std::size_t fit = 0;
  const double spent = cpu.seconds();
  while (fit < todo.size() && spent + total + estimate(todo[fit]) <= o.budget_cpu_seconds)
    total += estimate(todo[fit++]);
  std::ostringstream msg;
  msg << "parametric: " << points.size() << " points (" << points.size() - todo.size()
      << " done or failed); CPU per "
      << "point: wedge " << unit["wedge"] << " s at " << kRefParticles << " disks, disc "
      << unit["disc"] << " s at R = " << kRefRadius
      << " d (scaled by disks^1.5, R^3, packing); estimate " << total << " CPU s for " << fit
      << " points, budget " << o.budget_cpu_seconds << " CPU s";
  if (fit < todo.size()) msg << "; " << todo.size() - fit << " most expensive points left out";
  scene::log_line(msg.str(), true);
  const std::vector<ParametricPoint> run_now(todo.begin(),
                                             todo.begin() + static_cast<std::ptrdiff_t>(fit));
  std::vector<std::string> left_out;
  for (std::size_t k = fit; k < todo.size(); ++k) left_out.push_back(point_key(todo[k]));

  scene::Progress progress("parametric", static_cast<double>(run_now.size()), "points");
  for_each_in_processes(static_cast<int>(run_now.size()), o.jobs, [&](int k) {
    const auto& p = run_now[static_cast<std::size_t>(k)];
    const bool ok = run_point(p, point_dir(o.out_dir, p));
    // Children finish out of order: count the points on disk, not k.
    const auto finished =
        std::count_if(run_now.begin(), run_now.end(), [&](const ParametricPoint& q) {
          return done(o.out_dir, q) || fs::exists(point_dir(o.out_dir, q) + "/failed.json");
        });
    progress.update(static_cast<double>(finished), point_key(p));
    return ok ? 0 : 1;
  });
  progress.finish();

  nlohmann::json rows = nlohmann::json::array();
  for (const auto& p : points) {
    const bool dropped =
        std::find(left_out.begin(), left_out.end(), point_key(p)) != left_out.end();
    rows.push_back(
        row_of(p, panels_of[point_key(p)], o.out_dir, dropped ? "over_budget" : "not_run"));
  }
  const nlohmann::json cost{{"points", points.size()},
                            {"run_now", run_now.size() + static_cast<std::size_t>(probes)},
                            {"over_budget", left_out},
                            {"estimate_cpu_seconds", total},
                            {"cpu_seconds", cpu.seconds()},
                            {"budget_cpu_seconds", o.budget_cpu_seconds},
                            {"unit_cpu_seconds", unit}};
  scene::log_line("parametric: " + std::to_string(cpu.seconds()) + " CPU s spent", true);
  const std::string src_docs = std::string(PIPELINE_SOURCE_DIR) + "/../docs";
  const std::string page = o.docs_page.empty() ? src_docs + "/parametric.md" : o.docs_page;
  // Figures go beside the page they are linked from, so a page written
  // elsewhere never overwrites the repository's figures.
  const std::string figs =
      !o.figures_dir.empty()
          ? o.figures_dir
          : (page == "-" ? o.out_dir : (fs::path(page).parent_path() / "figures" / "parametric").string());
  write_parametric_outputs(rows, panels, cost, o.out_dir, figs, page);
  if (scene::interrupted())
    throw scene::RunError(
        "interrupted: the points done are kept and tabulated; rerun the same command to resume");
  return rows;
}

}  // namespace pipeline
