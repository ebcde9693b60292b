#include "pipeline/compare.hpp"

#include "pipeline/equal_error.hpp"

#include <algorithm>
#include <cmath>

#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;
// CFD wall time of the uniform family at error `e`: the cheapest run
// already that accurate, or the log-log crossing between two runs adjacent
// in time (equal_error.hpp); NaN when no uniform run reaches `e`.
double uniform_time_at(const std::vector<const GridRun*>& u, double e) {
  std::vector<CostError> runs;
  for (const GridRun* r : u) runs.push_back({r->cfd_wall_seconds, r->error, 0.0});
  return cheapest_cost_at(runs, e);
}

}  // namespace

nlohmann::json GridRun::to_json() const {
  return {{"family", family},
          {"level", level},
          {"cells", cells},
          {"mesh_seconds", mesh_seconds},
          {"cfd_wall_seconds", cfd_wall_seconds},
          {"steps", steps},
          {"steady_state_reached", steady},
          {"shock", shock},
          {"value", value},
          {"value_ci", value_ci},
          {"error", error},
          {"wall_pressure_ratio", wall_pressure_ratio},
          {"pressure_error", pressure_error},
          {"speedup_cfd_at_equal_error", speedup_cfd},
          {"cpu_seconds", cfd_cpu_seconds},
          {"mesh_cpu_seconds", mesh_cpu_seconds},
          {"wall_seconds", cfd_wall_seconds},
          {"flow_throughs", flow_throughs},
          {"cpu_us_per_cell_step", cpu_us_per_cell_step()},
          {"primary_error", primary_error},
          {"primary_error_ci", primary_error_ci},
          {"l1_density", l1_density},
          {"l1_density_ci", l1_density_ci},
          {"l1_pressure", l1_pressure},
          {"stagnation_pressure_ratio", stagnation_pressure_ratio},
          {"stagnation_pressure_error", stagnation_pressure_error},
          {"stagnation_pressure_error_ci", stagnation_pressure_error_ci},
          {"l1_total_enthalpy", l1_total_enthalpy},
          {"shock_axis_deviation_cells", shock_axis_deviation_cells},
          {"drag_coefficient", drag_coefficient},
          {"scheme", scheme},
          {"case", case_name},
          {"mesh", mesh_name},
          {"strips", strips},
          {"note", note}};
}

double GridRun::cpu_us_per_cell_step() const {
  return cells > 0 && steps > 0
             ? 1e6 * cfd_cpu_seconds / (static_cast<double>(cells) * static_cast<double>(steps))
             : scene::kNaN;
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
  const double e = cl.error;
  // Uniform match: the coarsest uniform at least as accurate.
  for (int k = 0; k < static_cast<int>(c.uniform.size()); ++k)
    if (std::isfinite(c.uniform[k].error) && c.uniform[k].error <= cl.error) { c.uniform_pick = k; c.uniform_matches = true; break; }
  if (c.uniform_pick < 0)
    for (int k = static_cast<int>(c.uniform.size()) - 1; k >= 0; --k)
      if (std::isfinite(c.uniform[k].error)) { c.uniform_pick = k; break; }
  std::sort(u.begin(), u.end(), [](const GridRun* a, const GridRun* b) { return a->cfd_wall_seconds < b->cfd_wall_seconds; });
  const double t_at = uniform_time_at(u, e);
  for (auto& r : c.clustered)
    r.speedup_cfd = std::isfinite(r.error) ? uniform_time_at(u, r.error) / r.cfd_wall_seconds : kNaN;
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
