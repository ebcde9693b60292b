#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>

#include "pipeline/calibration.hpp"
#include "pipeline/plot.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Point {
  double e, angle, ci;
};

// A sweep point counts only when the fit found a physical attached angle with
// a usable interval (a failed fit can return any number).
constexpr double kMaxUsableCiDeg = 5.0;
bool usable(const Point& p) {
  return std::isfinite(p.angle) && p.angle > 0.0 && p.angle < 90.0 && std::isfinite(p.ci) && p.ci < kMaxUsableCiDeg;
}

// Linear interpolation of e where angle(e) crosses `target`, scanning from
// e = 1 downwards (the physically relevant, least dissipative crossing).
// The 95% half-width on e propagates the angle intervals through the local slope.
bool crossing(const std::vector<Point>& pts, double target, double& e, double& e_ci) {
  if (pts.size() < 2) return false;
  for (std::size_t k = pts.size() - 1; k >= 1; --k) {
    const Point a = pts[k - 1], b = pts[k];
    if (!usable(a) || !usable(b)) continue;
    if ((a.angle - target) * (b.angle - target) <= 0 && a.angle != b.angle) {
      const double slope = (b.angle - a.angle) / (b.e - a.e);
      e = a.e + (target - a.angle) / slope;
      e_ci = std::abs(0.5 * (a.ci + b.ci) / slope);
      return true;
    }
  }
  return false;
}
}  // namespace

nlohmann::json run_calibration(const CalibrateOptions& o) {
  std::vector<std::string> scenes = o.scenes;
  if (scenes.empty())
    for (const auto& p : case_study_scenes())
      if (fs::path(p).filename().string().rfind("wedge", 0) == 0) scenes.push_back(p);
  if (scenes.empty()) throw scene::InputError("calibrate: no wedge scenes given");
  const std::string table_path = o.table_path.empty() ? builtin_calibration_path() : o.table_path;
  scene::make_dirs(o.out_dir);
  CalibrationTable table;
  nlohmann::json out = nlohmann::json::array();
  PlotSpec plot{"Granular shock angle against restitution (dashed: ideal-gas angle)", "restitution e",
                "shock angle (deg)", false, false, {}, {}};
  scene::Progress progress("calibrate", static_cast<double>(scenes.size() * o.restitutions.size()), "runs");
  int done = 0;
  for (const auto& path : scenes) {
    const scene::Scene base = scene::load_scene(path);
    if (!base.body || base.body->kind != scene::BodyKind::wedge)
      throw scene::InputError(path + ": calibrate needs wedge scenes");
    const double mach = base.freestream.mach, theta = base.body->angle_deg;
    const auto beta = scene::oblique_shock_beta(mach, theta * kDeg, 1.4);
    if (!beta) throw scene::InputError(path + ": detached at gamma 1.4; no shock angle to calibrate against");
    const double gas = *beta / kDeg;
    std::vector<Point> pts;
    Series ser;
    ser.title = base.name;
    for (const double e : o.restitutions) {
      scene::Scene s = base;
      s.granular.restitution = e;
      s.granular.restitution_given = true;
      std::ostringstream dir;
      dir << o.out_dir << "/" << base.name << "/e" << e;
      const auto r = run_prediction(s, dir.str(), o.np);
      const double a = r.contains("shock_angle_deg") && r["shock_angle_deg"].is_number() ? r["shock_angle_deg"].get<double>() : kNaN;
      const double ci = r.contains("shock_angle_ci_deg") && r["shock_angle_ci_deg"].is_number() ? r["shock_angle_ci_deg"].get<double>() : kNaN;
      pts.push_back({e, a, ci});
      progress.update(++done, base.name + " e=" + std::to_string(e));
      if (scene::interrupted()) throw scene::RunError("calibrate interrupted; finished runs are cached, rerun to resume");
    }
    std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.e < b.e; });
    nlohmann::json row = {{"scene", base.name}, {"mach", mach}, {"angle_deg", theta}, {"gas_angle_deg", gas}};
    nlohmann::json sweep = nlohmann::json::array();
    for (const auto& p : pts) sweep.push_back({{"restitution", p.e}, {"shock_angle_deg", p.angle}, {"ci_deg", p.ci}});
    row["sweep"] = sweep;
    double e = kNaN, e_ci = kNaN;
    if (crossing(pts, gas, e, e_ci)) {
      CalibrationEntry c{mach, theta, e, e_ci, gas, kNaN, kNaN};
      if (o.verify) {
        scene::Scene s = base;
        s.granular.restitution = e;
        s.granular.restitution_given = true;
        const auto r = run_prediction(s, o.out_dir + "/" + base.name + "/verify", o.np);
        c.granular_angle_deg = r.value("shock_angle_deg", kNaN);
        c.granular_angle_ci_deg = r.value("shock_angle_ci_deg", kNaN);
      }
      table.entries.push_back(c);
      row["restitution"] = e;
      row["restitution_ci"] = e_ci;
      row["verified_angle_deg"] = c.granular_angle_deg;
    } else {
      row["restitution"] = nullptr;
      row["note"] = "the granular angle does not cross the gas angle over the swept e";
    }
    out.push_back(row);
    for (const auto& p : pts) {
      if (!usable(p)) continue;  // failed fits stay in calibration.json, not on the plot
      ser.x.push_back(p.e);
      ser.y.push_back(p.angle);
      ser.yerr.push_back(p.ci);
    }
    plot.series.push_back(ser);
    std::ostringstream hl;
    hl << "set arrow from " << o.restitutions.front() << "," << gas << " to " << o.restitutions.back() << "," << gas
       << " nohead dt 2 lw 1.5";
    plot.extra.push_back(hl.str());
  }
  progress.finish();
  plot_png(plot, o.out_dir + "/calibration.png");
  write_calibration(table, table_path);
  scene::write_json_atomic(o.out_dir + "/calibration.json", out);
  return out;
}

}  // namespace pipeline
