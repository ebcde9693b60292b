#include "cfd/run_case.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "case_monitor.hpp"
#include "case_setup.hpp"
#include "foam_process.hpp"
#include "log_follower.hpp"
#include "scene/units.hpp"
#include "steady_state.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace cfd {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
// How often the monitor looks at the log and the case (seconds). Short
// against a write interval (tenths of seconds to seconds of wall time).
constexpr double kPollSeconds = 0.05;
// After asking the solver to stop (stopAt noWriteNow), how long to wait for
// it to notice before sending SIGTERM: it re-reads controlDict every step.
constexpr double kStopGraceSeconds = 30.0;
// Slack when comparing a written time with logged step times.
constexpr double kTimeSlack = 1e-9;

// Stopping the solver through controlDict (stopAt noWriteNow) can leave a
// time directory that holds only `uniform/`: the stop lands after the time
// was opened for writing but before any field was written. Such a directory
// is no solution; remove it so neither the monitor nor the resampling (which
// takes the latest time) reads it.
void remove_incomplete_times(const std::string& case_dir) {
  std::vector<std::string> dirs{case_dir};
  for (const auto& e : fs::directory_iterator(case_dir))
    if (e.is_directory() && e.path().filename().string().rfind("processor", 0) == 0) dirs.push_back(e.path().string());
  for (const auto& d : dirs)
    for (const TimeDir& t : time_dirs(d))
      if (!fs::exists(d + "/" + t.name + "/rho")) fs::remove_all(d + "/" + t.name);
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why a solver run ended badly, from its exit code and log.
std::string diagnose(int rc, const std::string& log_path) {
  const std::string log = scene::read_file(log_path);
  if (log.find("sigFpe") != std::string::npos || rc == 128 + SIGFPE)
    return "the solution diverged (floating-point exception in rhoCentralFoam)";
  if (log.find("Negative initial temperature") != std::string::npos || log.find("Negative temperature") != std::string::npos)
    return "the solution diverged (negative temperature)";
  if (log.find("Maximum number of iterations exceeded") != std::string::npos)
    return "the solution diverged (temperature iteration failed)";
  return fmt::format("rhoCentralFoam failed (exit {})", rc);
}

[[noreturn]] void fail_run(const std::string& what, const std::string& log) {
  throw scene::RunError(what + "; see " + log + ":" + log_tail(log));
}
}  // namespace

nlohmann::json CaseResult::summary() const {
  nlohmann::json j;
  j["steady_state_reached"] = steady_state_reached;
  j["wall_seconds"] = wall_seconds;
  j["cpu_seconds"] = cpu_seconds;
  const double cell_steps = static_cast<double>(cells) * static_cast<double>(steps);
  constexpr double kMicro = 1e6;
  j["cpu_us_per_cell_step"] = cell_steps > 0 ? nlohmann::json(cpu_seconds * kMicro / cell_steps) : nlohmann::json();
  j["sim_time"] = sim_time;
  j["flow_through_time"] = flow_through_time;
  j["flow_throughs"] = flow_through_time > 0 ? sim_time / flow_through_time : 0.0;
  j["steps"] = steps;
  j["cells"] = cells;
  j["wall_pressure_ratio"] = std::isfinite(wall_pressure_ratio) ? nlohmann::json(wall_pressure_ratio) : nlohmann::json();
  j["final_density_change_l2"] = final_density_change_l2;
  j["final_density_change_max"] = final_density_change_max;
  j["final_force_change"] = final_force_change;
  j["local_time_stepping"] = local_time_stepping;
  j["np"] = np;
  j["case_dir"] = case_dir;
  j["history_csv"] = history_csv;
  return j;
}

CaseResult run_case(const scene::Scene& s, const std::string& mesh_dir, const std::string& case_dir,
                    const CaseOptions& o) {
  if (!s.body) throw scene::InputError(s.source_file + ": cfd needs a scene with a body");
  if (!fs::exists(fs::path(mesh_dir) / "constant/polyMesh/faces"))
    throw scene::InputError(mesh_dir + ": no constant/polyMesh (run meshgen or cfd blockmesh first)");
  const fs::path mesh_abs = fs::weakly_canonical(mesh_dir), case_abs = fs::weakly_canonical(case_dir);
  const auto rel = mesh_abs.lexically_relative(case_abs);
  if (!rel.empty() && *rel.begin() != "..")
    throw scene::InputError(mesh_dir + ": the mesh directory lies inside the case directory " + case_dir +
                            ", which is replaced");
  const Mesh2D mesh = read_mesh_2d(mesh_dir);
  check_patches(mesh, mesh_dir);
  const scene::CfdParams& p = s.cfd;
  const Freestream f = freestream(s);
  const scene::Domain d = scene::scene_domain(s);

  CaseSettings cs;
  cs.np = o.np > 1 ? o.np : p.np;
  cs.lts = o.local_time_stepping.value_or(p.local_time_stepping);
  cs.flow_through = d.width() / f.mach;
  cs.dt_ref = free_stream_time_step(mesh, f, p.max_co);
  cs.lts_smoothing = o.lts_smoothing.value_or(kLtsSmoothingCoeff);
  // LTS marches in pseudo-time, each step advancing it by dt_ref, the
  // smallest cell's step; a flow-through of pseudo-time is then as many
  // steps as a time-accurate run takes, whatever the local steps gain. So
  // under LTS a "flow-through" is counted in iterations (the steps a signal
  // at the local Courant number needs to cross the domain), and end_time,
  // the written times (one per window of write_steps iterations) and the
  // per-flow-through measures all use that count.
  const long lts_steps = lts_steps_per_flow_through(mesh, f, p.max_co, d.width());
  const double norm_time = cs.lts ? static_cast<double>(lts_steps) * cs.dt_ref : cs.flow_through;
  cs.end_time = p.end_time * norm_time;
  cs.write_interval = p.write_interval * norm_time;
  cs.write_steps = std::max(1L, std::lround(cs.write_interval / cs.dt_ref));
  const std::string cdir = case_abs.string();
  write_case(s, mesh_abs.string(), cdir, cs);

  CaseResult r;
  r.case_dir = cdir;
  r.history_csv = cdir + "/history.csv";
  r.cells = static_cast<long>(mesh.cells());
  r.flow_through_time = cs.flow_through;
  r.local_time_stepping = cs.lts;
  r.np = cs.np;
  r.wall_pressure_ratio = scene::kNaN;

  if (cs.np > 1) r.cpu_seconds += run_foam(cdir, "decomposePar", {"-force"}).cpu_seconds;
  const CaseReader reader(s, cdir, cs.np);

  const auto t0 = Clock::now();
  FoamProcess solver(cdir, "rhoCentralFoam", {}, cs.np);
  LogFollower log(solver.log_path());
  scene::Progress progress("rhoCentralFoam " + s.name, p.end_time, "flow-throughs");
  std::optional<Snapshot> prev;
  SteadyState rule(cs.lts ? SteadyCriteria::iteration_windows(p, lts_steps)
                          : SteadyCriteria::time_accurate(p));
  double processed = 0.0;
  bool stop_requested = false, user_stop = false;
  Clock::time_point stop_at;
  auto request_stop = [&] {
    if (stop_requested) return;
    set_control(cdir, "stopAt", "noWriteNow");
    stop_requested = true;
    stop_at = Clock::now();
  };
  for (;;) {
    const bool exited = solver.poll();
    if (exited) remove_incomplete_times(cdir);
    log.update();
    if (log.diverged()) {
      solver.terminate();
      solver.wait();
      fail_run("the solution diverged (" + log.divergence() + ")", solver.log_path());
    }
    for (const TimeDir& t : reader.times_after(processed)) {
      // A written time is complete once the solver has logged a later step
      // (in parallel, that step's Courant reduction waits for every rank).
      if (!exited && !(log.last_time() > t.time + kTimeSlack * std::max(1.0, t.time))) break;
      Snapshot snap;
      try {
        snap = reader.read(t);
      } catch (const scene::RunError& e) {
        solver.terminate();
        solver.wait();
        fail_run(e.what(), solver.log_path());
      }
      if (prev) {
        HistoryRow row = compare(*prev, snap, reader.parts(), f.rho(), norm_time);
        row.wall_seconds = seconds_since(t0);
        row.steps = log.steps_upto(t.time);
        rule.add(row);
        if (rule.steady() && !r.steady_state_reached) {
          r.steady_state_reached = true;
          request_stop();
        }
        progress.update(row.flow_throughs, fmt::format("drho {:.2e} dF {:.2e}", row.drho_l2, row.dforce));
      }
      prev = std::move(snap);
      processed = t.time;
      if (!rule.rows().empty()) write_history(cdir, rule.rows(), p.steady_tol, p.force_tol, false);
    }
    if (exited) break;
    if (scene::interrupted() && !stop_requested) {
      user_stop = true;
      request_stop();
    }
    if (stop_requested && seconds_since(stop_at) > kStopGraceSeconds) solver.terminate();
    std::this_thread::sleep_for(std::chrono::duration<double>(kPollSeconds));
  }
  r.wall_seconds = seconds_since(t0);
  log.update();
  r.steps = log.steps();
  const int rc = solver.exit_code();
  r.cpu_seconds += solver.cpu_seconds();
  // Ready for a rerun by hand (Allrun) from the latest time.
  set_control(cdir, "stopAt", "endTime");
  if (rc != 0 && !stop_requested) fail_run(diagnose(rc, solver.log_path()), solver.log_path());
  progress.finish(r.steady_state_reached ? rule.why() : "not steady; " + rule.why());
  if (user_stop) throw scene::RunError("interrupted; the case is kept in " + cdir);
  if (cs.np > 1) r.cpu_seconds += run_foam(cdir, "reconstructPar", {"-latestTime"}).cpu_seconds;
  write_history(cdir, rule.rows(), p.steady_tol, p.force_tol, true);
  if (prev) {
    r.sim_time = prev->time;
    r.wall_pressure_ratio = prev->wall_pressure_ratio;
  }
  if (!rule.rows().empty()) {
    r.final_density_change_l2 = rule.rows().back().drho_l2;
    r.final_density_change_max = rule.rows().back().drho_max;
    r.final_force_change = rule.rows().back().dforce;
  }

  scene::write_json_atomic(cdir + "/summary.json", r.summary());
  return r;
}

}  // namespace cfd
