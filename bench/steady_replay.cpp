// The steady-state rule replayed on recorded cfd cases (every written time
// kept): each time is read with the case monitor's reader, the history rows
// recomputed, and the rule without and with the bow-shock drift gate fed
// row by row. Prints, per case, where each would have stopped and the
// shock's drift (least-squares slope over the gate's window) there; the
// numbers of docs/reliability.md ("Bow shocks that drift").
//
//   steady_replay [--rows] [--csv OUTDIR] [--default-tolerances] CASEDIR...
//
// CASEDIR: a `cfd run` case (scene.yaml, history.csv, the time directories),
// only read. --rows also prints each row's shock position and drift; --csv
// writes the recomputed history (history.csv's columns, under the new rule)
// to OUTDIR/<CASEDIR with '/' as '_'>.csv; --default-tolerances judges
// with the default steady_tol, force_tol, min_time and steady_checks instead
// of the case's own (diagnostic runs that disabled the rule).
#include <fmt/format.h>

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

struct Options {
  bool print_rows = false, default_tolerances = false;
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
  cfd::SteadyState old_rule(old_c), new_rule(old_c.with_shock_drift_gate(s));
  const scene::BodyGeometry g = scene::make_body(*s.body);
  std::optional<cfd::Snapshot> prev;
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
