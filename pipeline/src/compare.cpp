#include "pipeline/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pipeline {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Errors below this are treated as this (log-log interpolation needs > 0).
constexpr double kErrorFloor = 1e-6;
// CFD wall time of the uniform family (sorted by time) at error `e`:
// log(time) interpolated linearly in log(error) between the bracketing runs;
// a coarser uniform run already as accurate gives its own time; NaN when no
// uniform run reaches `e`.
double uniform_time_at(const std::vector<const GridRun*>& u, double e) {
  for (std::size_t k = 0; k + 1 < u.size(); ++k) {
    const double e0 = std::max(u[k]->error, kErrorFloor), e1 = std::max(u[k + 1]->error, kErrorFloor);
    if ((e0 - e) * (e1 - e) <= 0 && e0 != e1) {
      const double f = (std::log(e) - std::log(e0)) / (std::log(e1) - std::log(e0));
      return std::exp(std::log(u[k]->cfd_wall_seconds) +
                      f * (std::log(u[k + 1]->cfd_wall_seconds) - std::log(u[k]->cfd_wall_seconds)));
    }
  }
  if (!u.empty() && std::max(u.front()->error, kErrorFloor) <= e) return u.front()->cfd_wall_seconds;
  return kNaN;
}

}  // namespace

nlohmann::json GridRun::to_json() const {
  return {{"family", family}, {"level", level}, {"cells", cells}, {"mesh_seconds", mesh_seconds},
          {"cfd_wall_seconds", cfd_wall_seconds}, {"steps", steps}, {"steady_state_reached", steady},
          {"shock", shock}, {"value", value}, {"value_ci", value_ci}, {"error", error},
          {"wall_pressure_ratio", wall_pressure_ratio}, {"pressure_error", pressure_error},
          {"speedup_cfd_at_equal_error", speedup_cfd}};
}

void score(GridRun& r, const Reference& ref) {
  if (!std::isfinite(r.value)) {
    r.error = kNaN;
  } else if (ref.quantity == "shock_angle_deg") {
    r.error = std::abs(r.value - ref.value);
  } else {
    r.error = std::abs(r.value - ref.value) / ref.value;
  }
  r.pressure_error = std::isfinite(ref.pressure_ratio) && std::isfinite(r.wall_pressure_ratio)
                         ? std::abs(r.wall_pressure_ratio - ref.pressure_ratio) / ref.pressure_ratio
                         : kNaN;
}

Comparison compare(std::vector<GridRun> clustered, std::vector<GridRun> uniform, double granular_seconds) {
  Comparison c;
  c.clustered = std::move(clustered);
  c.uniform = std::move(uniform);
  c.speedup_cfd = c.speedup_total = c.speedup_bound = c.speedup_total_bound = kNaN;
  // Headline clustered run: the finest one with a finite error.
  for (int k = static_cast<int>(c.clustered.size()) - 1; k >= 0; --k)
    if (std::isfinite(c.clustered[k].error)) { c.clustered_pick = k; break; }
  std::vector<const GridRun*> u;
  for (const auto& r : c.uniform)
    if (std::isfinite(r.error) && r.cfd_wall_seconds > 0) u.push_back(&r);
  if (c.clustered_pick < 0 || u.empty()) return c;
  const GridRun& cl = c.clustered[c.clustered_pick];
  const double e = std::max(cl.error, kErrorFloor);
  // Uniform match: the coarsest uniform at least as accurate.
  for (int k = 0; k < static_cast<int>(c.uniform.size()); ++k)
    if (std::isfinite(c.uniform[k].error) && c.uniform[k].error <= cl.error) { c.uniform_pick = k; c.uniform_matches = true; break; }
  if (c.uniform_pick < 0)
    for (int k = static_cast<int>(c.uniform.size()) - 1; k >= 0; --k)
      if (std::isfinite(c.uniform[k].error)) { c.uniform_pick = k; break; }
  std::sort(u.begin(), u.end(), [](const GridRun* a, const GridRun* b) { return a->cfd_wall_seconds < b->cfd_wall_seconds; });
  const double t_at = uniform_time_at(u, e);
  for (auto& r : c.clustered)
    r.speedup_cfd = std::isfinite(r.error) ? uniform_time_at(u, std::max(r.error, kErrorFloor)) / r.cfd_wall_seconds : kNaN;
  const double clustered_total = cl.cfd_wall_seconds + cl.mesh_seconds + granular_seconds;
  if (std::isfinite(t_at)) {
    c.speedup_cfd = t_at / cl.cfd_wall_seconds;
    c.speedup_total = t_at / clustered_total;  // uniform meshing time is negligible and left out
  } else {
    c.speedup_bound = u.back()->cfd_wall_seconds / cl.cfd_wall_seconds;
    c.speedup_total_bound = u.back()->cfd_wall_seconds / clustered_total;
  }
  return c;
}

}  // namespace pipeline
