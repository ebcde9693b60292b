// One restart with robust settings when a run diverges.
#include <algorithm>

#include <fmt/format.h>

#include "cfd/run_case.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace cfd {

namespace {
// Half the Courant number: the restart trades steps for stability.
constexpr double kFallbackCourantFactor = 0.5;
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
    scene::log_line("cfd: " + first_line + "; restarting from the initial state with " + what, true);
    CaseResult r = run_case(robust, mesh_dir, case_dir, o);
    r.fallback = what + " (after: " + first_line + ")";
    r.cpu_seconds += first.cpu_seconds;
    r.wall_seconds += first.wall_seconds;
    r.steps += first.steps;
    scene::write_json_atomic(r.case_dir + "/summary.json", r.summary());
    return r;
  }
}

}  // namespace cfd
