// The restart when a run diverges: a bridge from the state before the
// divergence, else the whole run again with robust settings.
#include <fmt/format.h>

#include <filesystem>
#include <optional>

#include "cfd/foam_reader.hpp"
#include "cfd/run_case.hpp"
#include "foam_process.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace cfd {
namespace fs = std::filesystem;

namespace {
// Half the Courant number: the restart trades steps for stability.
constexpr double kFallbackCourantFactor = 0.5;

// What the attempts before the one that finished spent.
struct Spent {
  double cpu = 0.0, wall = 0.0;
  long steps = 0;
  void add(double c, double w, long n) {
    cpu += c;
    wall += w;
    steps += n;
  }
  void add(const Diverged& d) { add(d.cpu_seconds, d.wall_seconds, d.steps); }
  void add(const CaseResult& r) { add(r.cpu_seconds, r.wall_seconds, r.steps); }
  void charge(CaseResult& r) const {
    r.cpu_seconds += cpu;
    r.wall_seconds += wall;
    r.steps += steps;
  }
};

// A folder beside the case for the states and logs that a rerun of the case
// would replace; removed with this object.
class Aside {
 public:
  explicit Aside(const std::string& case_dir) {
    fs::path dir = fs::weakly_canonical(case_dir);
    if (dir.filename().empty())
      dir = dir.parent_path();  // "case/" names the case, not a folder in it
    path_ = dir.string() + ".restart";
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  Aside(const Aside&) = delete;
  Aside& operator=(const Aside&) = delete;
  ~Aside() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

  // The attempt's log and history, to be put back as NAME.TAG.
  void keep_attempt(const std::string& case_dir, const std::string& tag) {
    for (const auto& [from, to] : {std::pair{"log.rhoCentralFoam", "log.rhoCentralFoam." + tag},
                                   std::pair{"history.csv", "history." + tag + ".csv"}})
      if (fs::exists(case_dir + "/" + from))
        fs::copy_file(case_dir + "/" + from, path_ + "/" + to,
                      fs::copy_options::overwrite_existing);
    kept_.push_back(tag);
  }
  void restore_attempts(const std::string& case_dir) const {
    for (const std::string& tag : kept_)
      for (const std::string& name : {"log.rhoCentralFoam." + tag, "history." + tag + ".csv"})
        if (fs::exists(path_ + "/" + name))
          fs::copy_file(path_ + "/" + name, case_dir + "/" + name,
                        fs::copy_options::overwrite_existing);
  }

 private:
  std::string path_;
  std::vector<std::string> kept_;
};

int ranks(const scene::Scene& s, const CaseOptions& o) {
  return o.np > 1 ? o.np : s.cfd.np;
}

// The written times of a case that run_case left, oldest first (it removes
// incomplete ones, however the solver ended).
std::vector<TimeDir> written_times(const std::string& case_dir, int np) {
  return time_dirs(np > 1 ? case_dir + "/processor0" : case_dir);
}

// The case's time `t` (reconstructed when parallel) copied aside; its path.
std::string set_aside(const std::string& case_dir, const TimeDir& t, int np, const Aside& aside,
                      Spent& spent) {
  if (np > 1)
    spent.add(run_foam(case_dir, "reconstructPar", {"-time", t.name}).cpu_seconds, 0.0, 0);
  const std::string to = aside.path() + "/" + t.name;
  fs::remove_all(to);
  fs::copy(case_dir + "/" + t.name, to, fs::copy_options::recursive);
  return to;
}

// The bridge: from the state written a write interval before the last one
// the divergence left (the last may already carry what diverged),
// kBridgeFlowThroughs with the robust settings, never judged steady, then
// the scene's own settings from where the bridge ended. nullopt where fewer
// than two states were written; Diverged where a stage diverges.
std::optional<CaseResult> bridge(const scene::Scene& s, const std::string& mesh_dir,
                                 const std::string& case_dir, const CaseOptions& o,
                                 double time_per_flow_through, Aside& aside, Spent& spent,
                                 std::string& what) {
  const int np = ranks(s, o);
  const std::vector<TimeDir> times = written_times(case_dir, np);
  if (times.size() < 2 || !(time_per_flow_through > 0.0)) return std::nullopt;
  const TimeDir& before = times[times.size() - 2];
  const std::string state = set_aside(case_dir, before, np, aside, spent);

  scene::Scene robust = s;
  std::string settings;
  robust.cfd = robust_settings(s.cfd, settings);
  const double from = before.time / time_per_flow_through;
  robust.cfd.end_time = from + kBridgeFlowThroughs;
  robust.cfd.min_time = robust.cfd.end_time + kBridgeFlowThroughs;  // the bridge is not the result
  CaseOptions bridge_options = o;
  bridge_options.continue_from = state;
  scene::log_line(fmt::format("cfd: bridging from {:.3g} flow-throughs with {}", from, settings),
                  true);
  const CaseResult b = run_case(robust, mesh_dir, case_dir, bridge_options);
  spent.add(b);
  aside.keep_attempt(case_dir, "bridge");

  const std::vector<TimeDir> bridged = written_times(case_dir, 1);
  if (bridged.empty()) return std::nullopt;
  CaseOptions own = o;
  own.continue_from = set_aside(case_dir, bridged.back(), 1, aside, spent);
  CaseResult r = run_case(s, mesh_dir, case_dir, own);
  what = fmt::format(
      "{} for {:g} flow-through from {:.3g} flow-throughs, then the scene's own settings", settings,
      kBridgeFlowThroughs, from);
  return r;
}

}  // namespace

scene::CfdParams robust_settings(const scene::CfdParams& p, std::string& what) {
  scene::CfdParams r = p;
  // Tadmor's flux is more dissipative than Kurganov's at strong shocks, and
  // Minmod the most dissipative TVD limiter; both damp the start-up
  // transients that drive a divergence.
  r.flux_scheme = "Tadmor";
  r.limiter = "Minmod";
  r.max_co = p.max_co * kFallbackCourantFactor;
  what = fmt::format("flux_scheme Tadmor, limiter Minmod, max_co {:g}", r.max_co);
  return r;
}

CaseResult run_case_with_fallback(const scene::Scene& s, const std::string& mesh_dir, const std::string& case_dir,
                                  const CaseOptions& o) {
  try {
    return run_case(s, mesh_dir, case_dir, o);
  } catch (const Diverged& first) {
    if (!s.cfd.fallback) throw;
    scene::Scene robust = s;
    std::string what;
    robust.cfd = robust_settings(s.cfd, what);
    if (robust.cfd.flux_scheme == s.cfd.flux_scheme && robust.cfd.limiter == s.cfd.limiter &&
        robust.cfd.max_co == s.cfd.max_co)
      throw;
    const std::string first_line = std::string(first.what()).substr(0, std::string(first.what()).find(';'));
    scene::log_line("cfd: " + first_line + "; restarting", true);
    Aside aside(case_dir);
    aside.keep_attempt(case_dir, "diverged");
    Spent spent;
    spent.add(first);
    std::optional<CaseResult> r;
    std::string how;
    try {
      r = bridge(s, mesh_dir, case_dir, o, first.time_per_flow_through, aside, spent, how);
    } catch (const Diverged& again) {
      spent.add(again);
      aside.keep_attempt(case_dir, "restart-diverged");
    }
    if (!r) {
      scene::log_line("cfd: restarting from the initial state with " + what, true);
      r = run_case(robust, mesh_dir, case_dir, o);
      how = what;
    }
    r->fallback = how + " (after: " + first_line + ")";
    spent.charge(*r);
    aside.restore_attempts(case_dir);
    scene::write_json_atomic(r->case_dir + "/summary.json", r->summary());
    return *r;
  }
}

}  // namespace cfd
