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
// it to notice before sending SIGTERM. It re-reads controlDict every step,
// but an edit that lands while it is still reading controlDict at start-up
// can go unseen (it records the new time stamp with the old text), so the
// request is backed by a signal well inside the interrupt watchdog's grace:
// Ctrl-C must end as a clean "interrupted" run, not as the watchdog's exit.
constexpr double kStopGraceSeconds = 10.0;
static_assert(kStopGraceSeconds < 0.5 * scene::kInterruptGraceSeconds);
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

// The template's timePrecision (system/controlDict). On a start OpenFOAM
// formats the time it reads from uniform/time at this precision and looks for
// the directory of that name, while the solver that wrote a time may have
// raised its precision to name it; so a state a run continues from is
// copied in under a name written at this precision.
constexpr int kTemplateTimePrecision = 10;

void place_state(const std::string& state_dir, const std::string& cdir) {
  const double t = std::stod(fs::path(state_dir).filename().string());
  fs::copy(state_dir, fmt::format("{}/{:.{}g}", cdir, t, kTemplateTimePrecision),
           fs::copy_options::recursive);
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why a solver run ended badly, from its exit code and log.
struct Diagnosis {
  std::string why;
  bool diverged = false;
};
Diagnosis diagnose(int rc, const std::string& log_path) {
  const std::string log = scene::read_file(log_path);
  if (log.find("sigFpe") != std::string::npos || rc == 128 + SIGFPE)
    return {"the solution diverged (floating-point exception in rhoCentralFoam)", true};
  if (log.find("Negative initial temperature") != std::string::npos || log.find("Negative temperature") != std::string::npos)
    return {"the solution diverged (negative temperature)", true};
  if (log.find("Maximum number of iterations exceeded") != std::string::npos)
    return {"the solution diverged (temperature iteration failed)", true};
  return {fmt::format("rhoCentralFoam failed (exit {})", rc), false};
}

[[noreturn]] void fail_run(const std::string& what, const std::string& log) {
  throw scene::RunError(what + "; see " + log + ":" + log_tail(log));
}

// A divergence is thrown as Diverged, so that a caller may restart.
[[noreturn]] void fail_diverged(const std::string& what, const std::string& log, double cpu,
                                double wall, long steps, double norm_time) {
  throw Diverged(what + "; see " + log + ":" + log_tail(log), cpu, wall, steps, norm_time);
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
  j["start"] = start;
  j["outflow"] = outflow;
  j["flux_scheme"] = flux_scheme;
  j["limiter"] = limiter;
  j["case_dir"] = case_dir;
  j["history_csv"] = history_csv;
  j["fallback"] = fallback.empty() ? nlohmann::json(nullptr) : nlohmann::json(fallback);
  return j;
}

namespace {

// The mesh and case directories, absolute. InputError for a mesh folder
// without a polyMesh or one inside the case folder (which is replaced).
struct CasePaths {
  std::string mesh, case_dir;
};

CasePaths checked_paths(const std::string& mesh_dir, const std::string& case_dir) {
  if (!fs::exists(fs::path(mesh_dir) / "constant/polyMesh/faces"))
    throw scene::InputError(mesh_dir + ": no constant/polyMesh (run meshgen or cfd blockmesh first)");
  const fs::path mesh_abs = fs::weakly_canonical(mesh_dir), case_abs = fs::weakly_canonical(case_dir);
  const auto rel = mesh_abs.lexically_relative(case_abs);
  if (!rel.empty() && *rel.begin() != "..")
    throw scene::InputError(mesh_dir + ": the mesh directory lies inside the case directory " + case_dir +
                            ", which is replaced");
  return {mesh_abs.string(), case_abs.string()};
}

// The run's clock: settings for the case files, and the time a
// flow-through counts for in the history.
struct Schedule {
  CaseSettings settings;
  long lts_steps = 0;      // LTS iterations per flow-through
  double norm_time = 0.0;  // one flow-through in the solver's (pseudo-)time
};

Schedule schedule(const scene::Scene& s, const CaseOptions& o, const Mesh2D& mesh,
                  const Freestream& f) {
  const scene::CfdParams& p = s.cfd;
  const scene::Domain d = scene::scene_domain(s);
  Schedule out;
  CaseSettings& cs = out.settings;
  cs.np = o.np > 1 ? o.np : p.np;
  cs.lts = o.local_time_stepping.value_or(local_time_stepping(s));
  cs.flow_through = d.width() / f.mach;
  cs.max_co = cs.lts ? p.max_co * kLtsCourantFactor : p.max_co;
  cs.dt_ref = free_stream_time_step(mesh, f, cs.max_co);
  cs.lts_smoothing = o.lts_smoothing.value_or(kLtsSmoothingCoeff);
  // LTS marches in pseudo-time, each step advancing it by dt_ref, the
  // smallest cell's step; a flow-through of pseudo-time is then as many
  // steps as a time-accurate run takes, whatever the local steps gain. So
  // under LTS a "flow-through" is counted in iterations (the steps a signal
  // at the local Courant number needs to cross the domain), and end_time,
  // the written times (one per window of write_steps iterations) and the
  // per-flow-through measures all use that count.
  out.lts_steps = lts_steps_per_flow_through(mesh, f, cs.max_co, d.width());
  out.norm_time = cs.lts ? static_cast<double>(out.lts_steps) * cs.dt_ref : cs.flow_through;
  cs.end_time = p.end_time * out.norm_time;
  cs.write_interval = p.write_interval * out.norm_time;
  cs.write_steps = std::max(1L, std::lround(cs.write_interval / cs.dt_ref));
  return out;
}

// A running solver under watch: each completely written time is compared
// with the one before, the steady-state rule fed and history.csv written; a
// stop is requested (stopAt noWriteNow) once the rule is met or on Ctrl-C,
// and the solver terminated when it ignores the request for
// kStopGraceSeconds. A divergence or an unreadable time fails the run.
class SolverWatch {
 public:
  SolverWatch(const scene::Scene& s, const std::string& cdir, const CaseReader& reader,
              FoamProcess& solver, const Schedule& sched, double rho_inf, Clock::time_point t0)
      : p_(s.cfd),
        cdir_(cdir),
        reader_(reader),
        solver_(solver),
        log_(solver.log_path()),
        progress_("rhoCentralFoam " + s.name, s.cfd.end_time, "flow-throughs"),
        rule_((sched.settings.lts ? SteadyCriteria::iteration_windows(s.cfd, sched.lts_steps)
                                  : SteadyCriteria::time_accurate(s.cfd))
                  .for_body(s)),
        rho_inf_(rho_inf),
        norm_time_(sched.norm_time),
        t0_(t0) {}

  // Until the solver exits.
  void run() {
    for (;;) {
      const bool exited = solver_.poll();
      if (exited) remove_incomplete_times(cdir_);
      log_.update();
      if (log_.diverged()) {
        end_solver();
        fail_diverged("the solution diverged (" + log_.divergence() + ")", solver_.log_path(),
                      solver_.cpu_seconds(), seconds_since(t0_), log_.steps(), norm_time_);
      }
      take_written_times(exited);
      if (exited) break;
      if (scene::interrupted() && !stop_requested_) {
        user_stop_ = true;
        request_stop();
      }
      if (stop_requested_ && seconds_since(stop_at_) > kStopGraceSeconds) solver_.terminate();
      std::this_thread::sleep_for(std::chrono::duration<double>(kPollSeconds));
    }
  }

  LogFollower& log() { return log_; }
  scene::Progress& progress() { return progress_; }
  const SteadyState& rule() const { return rule_; }
  double norm_time() const { return norm_time_; }
  const std::optional<Snapshot>& last() const { return prev_; }
  bool steady() const { return steady_; }
  bool stop_requested() const { return stop_requested_; }
  bool user_stop() const { return user_stop_; }

 private:
  // The solver ended on a failure: the case is kept, with only complete
  // states in it (a restart continues from them).
  void end_solver() {
    solver_.terminate();
    solver_.wait();
    remove_incomplete_times(cdir_);
  }

  void request_stop() {
    if (stop_requested_) return;
    set_control(cdir_, "stopAt", "noWriteNow");
    stop_requested_ = true;
    stop_at_ = Clock::now();
  }

  void take_written_times(bool exited) {
    for (const TimeDir& t : reader_.times_after(processed_)) {
      // A written time is complete once the solver has logged a later step
      // (in parallel, that step's Courant reduction waits for every rank).
      if (!exited && !(log_.last_time() > t.time + kTimeSlack * std::max(1.0, t.time))) break;
      Snapshot snap;
      try {
        snap = reader_.read(t);
      } catch (const NonPhysicalState& e) {
        end_solver();
        fail_diverged(e.what(), solver_.log_path(), solver_.cpu_seconds(), seconds_since(t0_),
                      log_.steps(), norm_time_);
      } catch (const scene::RunError& e) {
        end_solver();
        fail_run(e.what(), solver_.log_path());
      }
      if (prev_) compare_with_previous(t, snap);
      prev_ = std::move(snap);
      processed_ = t.time;
      if (!rule_.rows().empty())
        write_history(cdir_, rule_.rows(), p_.steady_tol, p_.force_tol, false);
    }
  }

  void compare_with_previous(const TimeDir& t, const Snapshot& snap) {
    HistoryRow row = compare(*prev_, snap, reader_.parts(), rho_inf_, norm_time_);
    row.wall_seconds = seconds_since(t0_);
    row.steps = log_.steps_upto(t.time);
    rule_.add(row);
    if (rule_.steady() && !steady_) {
      steady_ = true;
      request_stop();
    }
    progress_.update(row.flow_throughs,
                     fmt::format("drho {:.2e} dF {:.2e}", row.drho_l2, row.dforce));
  }

  const scene::CfdParams& p_;
  const std::string& cdir_;
  const CaseReader& reader_;
  FoamProcess& solver_;
  LogFollower log_;
  scene::Progress progress_;
  SteadyState rule_;
  double rho_inf_, norm_time_;
  Clock::time_point t0_;
  std::optional<Snapshot> prev_;
  double processed_ = 0.0;
  bool steady_ = false, stop_requested_ = false, user_stop_ = false;
  Clock::time_point stop_at_;
};

// After the solver: its cost and exit, the case left ready for a rerun by
// hand, the parallel case reconstructed, the final history and state.
void finish_run(CaseResult& r, SolverWatch& watch, FoamProcess& solver, const scene::CfdParams& p,
                Clock::time_point t0) {
  const std::string& cdir = r.case_dir;
  r.wall_seconds = seconds_since(t0);
  watch.log().update();
  r.steps = watch.log().steps();
  const int rc = solver.exit_code();
  r.cpu_seconds += solver.cpu_seconds();
  // Ready for a rerun by hand (Allrun) from the latest time.
  set_control(cdir, "stopAt", "endTime");
  if (rc != 0 && !watch.stop_requested()) {
    const Diagnosis d = diagnose(rc, solver.log_path());
    if (d.diverged)
      fail_diverged(d.why, solver.log_path(), r.cpu_seconds, r.wall_seconds, r.steps,
                    watch.norm_time());
    fail_run(d.why, solver.log_path());
  }
  r.steady_state_reached = watch.steady();
  watch.progress().finish(r.steady_state_reached ? watch.rule().why()
                                                 : "not steady; " + watch.rule().why());
  if (watch.user_stop()) throw scene::RunError("interrupted; the case is kept in " + cdir);
  if (r.np > 1) r.cpu_seconds += run_foam(cdir, "reconstructPar", {"-latestTime"}).cpu_seconds;
  const std::vector<HistoryRow>& rows = watch.rule().rows();
  write_history(cdir, rows, p.steady_tol, p.force_tol, true);
  if (watch.last()) {
    r.sim_time = watch.last()->time;
    r.wall_pressure_ratio = watch.last()->wall_pressure_ratio;
  }
  if (!rows.empty()) {
    r.final_density_change_l2 = rows.back().drho_l2;
    r.final_density_change_max = rows.back().drho_max;
    r.final_force_change = rows.back().dforce;
  }
}

}  // namespace

CaseResult run_case(const scene::Scene& s, const std::string& mesh_dir, const std::string& case_dir,
                    const CaseOptions& o) {
  if (!s.body) throw scene::InputError(s.source_file + ": cfd needs a scene with a body");
  const CasePaths paths = checked_paths(mesh_dir, case_dir);
  const Mesh2D mesh = read_mesh_2d(mesh_dir);
  check_patches(mesh, mesh_dir);
  const Freestream f = freestream(s);
  const Schedule sched = schedule(s, o, mesh, f);
  const CaseSettings& cs = sched.settings;
  const std::string& cdir = paths.case_dir;
  write_case(s, paths.mesh, mesh, cdir, cs);
  if (!o.continue_from.empty()) place_state(o.continue_from, cdir);

  CaseResult r;
  r.case_dir = cdir;
  r.history_csv = cdir + "/history.csv";
  r.cells = static_cast<long>(mesh.cells());
  r.flow_through_time = cs.flow_through;
  r.local_time_stepping = cs.lts;
  r.np = cs.np;
  r.start = initial_state(s);
  r.outflow = subsonic_outflow(s) ? "subsonic" : "supersonic";
  r.flux_scheme = flux_scheme(s);
  r.limiter = limiter(s);
  r.wall_pressure_ratio = scene::kNaN;

  // A continued run needs only the state it continues from on the ranks.
  const std::vector<std::string> decompose =
      o.continue_from.empty() ? std::vector<std::string>{"-force"}
                              : std::vector<std::string>{"-force", "-latestTime"};
  if (cs.np > 1) r.cpu_seconds += run_foam(cdir, "decomposePar", decompose).cpu_seconds;
  const CaseReader reader(s, cdir, cs.np);
  const auto t0 = Clock::now();
  FoamProcess solver(cdir, "rhoCentralFoam", {}, cs.np);
  SolverWatch watch(s, cdir, reader, solver, sched, f.rho(), t0);
  watch.run();
  finish_run(r, watch, solver, s.cfd, t0);
  scene::write_json_atomic(cdir + "/summary.json", r.summary());
  return r;
}

}  // namespace cfd
