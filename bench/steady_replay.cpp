// The steady-state rule replayed on recorded cfd cases (every written time
// kept): each time is read with the case monitor's reader, the history rows
// recomputed, and the rule without and with the bow-shock drift gate fed
// row by row. Prints, per case, where each would have stopped and the
// shock's drift (least-squares slope over the gate's window) there; the
// numbers of docs/reliability.md ("Bow shocks that drift").
//
//   steady_replay [--rows] [--csv OUTDIR] [--default-tolerances] [--errors] [--error-history]
//                 CASEDIR...
//
// CASEDIR: a `cfd run` case (scene.yaml, history.csv, the time directories),
// only read. --rows also prints each row's shock position and drift; --csv
// writes the recomputed history (history.csv's columns, under the new rule)
// to OUTDIR/<CASEDIR with '/' as '_'>.csv; --default-tolerances judges
// with the default steady_tol, force_tol, min_time and steady_checks instead
// of the case's own (diagnostic runs that disabled the rule); --errors also
// measures the verdict's primary error at the current rule's stop and at the
// recorded run's last written time (its stop), each from that time and the
// one before, as the pipeline measures a finished grid; --error-history
// measures it at every written time (error against steps: where a run
// that ignored the rule would have reached a given error).
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "case_monitor.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/verdict.hpp"
#include "scene/body.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"
#include "steady_state.hpp"

namespace fs = std::filesystem;

namespace {

// The recorded history's clock: one flow-through in solver time, and the
// solver steps at each written time.
struct Recorded {
  double norm_time = 0;
  std::map<double, long> steps;
};

Recorded recorded_history(const std::string& case_dir, const scene::Scene& s) {
  Recorded r;
  std::ifstream in(case_dir + "/history.csv");
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string f;
    std::vector<std::string> cols;
    while (std::getline(ss, f, ',')) cols.push_back(f);
    if (cols.size() < 4) continue;
    const double t = std::stod(cols[0]), ft = std::stod(cols[1]);
    if (r.norm_time == 0 && ft > 0) r.norm_time = t / ft;
    r.steps[t] = std::stol(cols[3]);
  }
  if (r.norm_time == 0) r.norm_time = scene::scene_domain(s).width() / s.freestream.mach;
  return r;
}

long steps_at(const Recorded& r, double t) {
  const auto it = r.steps.lower_bound(t * (1 - 1e-9));
  return it == r.steps.end() ? 0 : it->second;
}

std::string ft(double v) {
  return std::isfinite(v) ? fmt::format("{:.1f}", v) : "-";
}
std::string num(double v) {
  return std::isfinite(v) ? fmt::format("{:+.3g}", v) : "-";
}

// history.csv writes times to 10 digits: a written time within this relative
// distance of a recorded one is that time.
constexpr double kSameTime = 1e-7;

// The primary error of the case as if its run had stopped at written time
// `stop`: measured on a scratch case that links the mesh, the dictionaries
// and the written times up to `stop`.
pipeline::MeasuredError error_at(const scene::Scene& s, const std::string& case_dir,
                                 const std::string& primary, double stop) {
  const fs::path scratch =
      fs::temp_directory_path() /
      fmt::format("steady_replay_{}_{}", ::getpid(), std::hash<std::string>{}(case_dir));
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  for (const char* d : {"constant", "system"})
    fs::create_directory_symlink(fs::absolute(fs::path(case_dir) / d), scratch / d);
  for (const cfd::TimeDir& t : cfd::time_dirs(case_dir))
    if (t.time <= stop * (1 + kSameTime))
      fs::create_directory_symlink(fs::absolute(fs::path(case_dir) / t.name), scratch / t.name);
  const pipeline::MeasuredError e =
      pipeline::measure_named(pipeline::measure_case_errors(s, scratch.string()), primary);
  fs::remove_all(scratch);
  return e;
}

struct Options {
  bool print_rows = false, default_tolerances = false, errors = false, error_history = false;
  std::string csv_dir;
};

void replay(const std::string& case_dir, const Options& o) {
  scene::Scene s = scene::load_scene(case_dir + "/scene.yaml");
  if (o.default_tolerances) {
    const scene::CfdParams d;
    s.cfd.steady_tol = d.steady_tol;
    s.cfd.force_tol = d.force_tol;
    s.cfd.min_time = d.min_time;
    s.cfd.steady_checks = d.steady_checks;
  }
  const bool print_rows = o.print_rows;
  const std::string& csv_dir = o.csv_dir;
  nlohmann::json sum;
  if (fs::exists(case_dir + "/summary.json")) std::ifstream(case_dir + "/summary.json") >> sum;
  const bool lts = sum.contains("local_time_stepping") && sum["local_time_stepping"].is_boolean() &&
                   sum["local_time_stepping"].get<bool>();
  const Recorded rec = recorded_history(case_dir, s);
  const cfd::CaseReader reader(s, case_dir, 1);
  const double rho_inf = cfd::freestream(s).rho();
  cfd::SteadyCriteria old_c = cfd::SteadyCriteria::time_accurate(s.cfd);
  if (lts) {
    // Iteration flow-throughs: steps per flow-through from the recorded rows.
    const auto last = rec.steps.rbegin();
    old_c = cfd::SteadyCriteria::iteration_windows(
        s.cfd, std::lround(static_cast<double>(last->second) / (last->first / rec.norm_time)));
  }
  cfd::SteadyState old_rule(old_c), new_rule(old_c.for_body(s));
  const scene::BodyGeometry g = scene::make_body(*s.body);
  std::optional<cfd::Snapshot> prev;
  std::vector<double> row_time;
  int old_at = -1, new_at = -1;
  std::string ended = "end";
  for (const cfd::TimeDir& t : reader.times_after(0.0)) {
    cfd::Snapshot snap;
    try {
      snap = reader.read(t);
    } catch (const std::exception& e) {
      ended = "diverged";
      break;
    }
    if (prev) {
      cfd::HistoryRow row = cfd::compare(*prev, snap, reader.parts(), rho_inf, rec.norm_time);
      row.steps = steps_at(rec, t.time);
      row_time.push_back(t.time);
      old_rule.add(row);
      new_rule.add(row);
      const int k = static_cast<int>(new_rule.rows().size()) - 1;
      if (old_at < 0 && old_rule.steady()) old_at = k;
      if (new_at < 0 && new_rule.steady()) new_at = k;
      if (print_rows) {
        const cfd::HistoryRow& r = new_rule.rows().back();
        std::printf("  %6.2f drho %.3g dF %.3g shock_x %s cell %s drift %s%s%s\n",
                    new_rule.progress(r), r.drho_l2, r.dforce, num(r.shock_x).c_str(),
                    num(r.shock_cell).c_str(), num(r.shock_drift).c_str(),
                    k == old_at ? "  <- old stop" : "", k == new_at ? "  <- new stop" : "");
      }
    }
    prev = std::move(snap);
  }
  // How many cells the stagnation line crosses ahead of the nose (0: the
  // line missed the grid, which would leave the gate blind).
  const auto probe = cfd::ShockProbe::for_scene(s, reader.parts());
  const std::size_t line_cells = probe ? probe->samples() : 0;
  const auto& rows = new_rule.rows();
  if (!csv_dir.empty()) {
    std::string name = case_dir;
    std::replace(name.begin(), name.end(), '/', '_');
    const std::string dir = csv_dir + "/" + name;
    fs::create_directories(dir);
    cfd::write_history(dir, rows, s.cfd.steady_tol, s.cfd.force_tol, false);
  }
  if (rows.empty()) {
    std::printf("%s: no rows\n", case_dir.c_str());
    return;
  }
  const auto at = [&](int k, auto f) {
    return k < 0 ? scene::kNaN : f(rows[static_cast<std::size_t>(k)]);
  };
  const auto ftk = [&](const cfd::HistoryRow& r) { return new_rule.progress(r); };
  const auto drift = [&](const cfd::HistoryRow& r) { return r.shock_drift / g.length; };
  const int last = static_cast<int>(rows.size()) - 1;
  const double standoff = (g.nose.x - rows.back().shock_x) / g.length;
  std::printf(
      "%s | %ld cells (%zu on the stagnation line) | rows to %.1f (%s) | old stop %s, drift %s "
      "L/ft | new stop %s, drift %s L/ft | last drift %s L/ft, cell %s L | standoff %s L | "
      "recorded steady %s | new why: %s\n",
      case_dir.c_str(), reader.cells(), line_cells, ftk(rows.back()), ended.c_str(),
      ft(at(old_at, ftk)).c_str(), num(at(old_at, drift)).c_str(), ft(at(new_at, ftk)).c_str(),
      num(at(new_at, drift)).c_str(), num(at(last, drift)).c_str(),
      num(rows.back().shock_cell / g.length).c_str(), num(standoff).c_str(),
      sum.contains("steady_state_reached") && sum["steady_state_reached"].is_boolean()
          ? (sum["steady_state_reached"].get<bool>() ? "yes" : "no")
          : "?",
      new_rule.why().c_str());
  if (o.errors && !rec.steps.empty()) {
    const std::string primary = pipeline::primary_error_for(s).name;
    const double end = rec.steps.rbegin()->first;
    const pipeline::MeasuredError at_end = error_at(s, case_dir, primary, end);
    const double stop = new_at < 0 ? end : row_time[static_cast<std::size_t>(new_at)];
    const pipeline::MeasuredError at_stop = error_at(s, case_dir, primary, stop);
    std::printf(
        "  %s | recorded stop %.2f ft, %ld steps, %.4g +- %.2g | new stop %.2f ft, %ld steps, "
        "%.4g +- %.2g | steps %.3f, error %+.4f relative\n",
        primary.c_str(), end / rec.norm_time, rec.steps.rbegin()->second, at_end.value,
        at_end.uncertainty, stop / rec.norm_time, steps_at(rec, stop), at_stop.value,
        at_stop.uncertainty,
        static_cast<double>(steps_at(rec, stop)) / static_cast<double>(rec.steps.rbegin()->second),
        at_stop.value / at_end.value - 1);
  }
  if (o.error_history) {
    const std::string primary = pipeline::primary_error_for(s).name;
    std::printf("  %s at every written time (progress in flow-throughs, steps, error +- change)\n",
                primary.c_str());
    for (std::size_t k = 0; k < row_time.size(); ++k) {
      const pipeline::MeasuredError e = error_at(s, case_dir, primary, row_time[k]);
      std::printf("    %6.2f %7ld %.5g +- %.2g%s\n", new_rule.progress(rows[k]),
                  steps_at(rec, row_time[k]), e.value, e.uncertainty,
                  static_cast<int>(k) == new_at ? "  <- rule's stop" : "");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--rows") {
      o.print_rows = true;
      continue;
    }
    if (a == "--errors") {
      o.errors = true;
      continue;
    }
    if (a == "--error-history") {
      o.error_history = true;
      continue;
    }
    if (a == "--default-tolerances") {
      o.default_tolerances = true;
      continue;
    }
    if (a == "--csv" && i + 1 < argc) {
      o.csv_dir = argv[++i];
      continue;
    }
    try {
      replay(a, o);
    } catch (const std::exception& e) {
      std::printf("%s: %s\n", a.c_str(), e.what());
    }
  }
  return 0;
}
