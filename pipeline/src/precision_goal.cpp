#include "pipeline/precision_goal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "json_fields.hpp"
#include "scene/body.hpp"
#include "scene/units.hpp"
#include "shockfit/group_interval.hpp"

namespace pipeline {

std::optional<double> precision_target(const scene::Scene& s) {
  const scene::GranularParams& p = s.granular;
  if (p.target_half_width) return *p.target_half_width;
  if (!p.target_from_mesh) return std::nullopt;
  const auto& levels = s.pipeline.levels;
  const double finest = levels.empty() ? 1.0 : *std::min_element(levels.begin(), levels.end());
  return kTargetFineCells * s.mesh.h_min * finest;
}

namespace {

// An attached shock pivots about the apex: the distance (body lengths) from
// the nose to its farthest accepted point is the lever that turns an angle
// into a displacement.
double attached_reach(const scene::Scene& s, const shockfit::ShockResult& r) {
  const scene::BodyGeometry g = scene::make_body(*s.body);
  double reach = 0.0;
  for (const auto& st : r.stations)
    if (st.accepted && std::isfinite(st.shock.x))
      reach = std::max(reach, scene::norm(st.shock - g.nose));
  return reach / g.length;
}

}  // namespace

double shock_position_half_width(const scene::Scene& s, const shockfit::ShockResult& r) {
  using scene::ShockKind;
  if (r.shock == ShockKind::detached) return r.standoff_ci;
  if (r.shock != ShockKind::attached || !s.body || !std::isfinite(r.shock_angle_ci_deg))
    return scene::kNaN;
  return attached_reach(s, r) * std::tan(r.shock_angle_ci_deg * scene::kDeg);
}

granular::PrecisionGoal precision_goal(const scene::Scene& s) {
  granular::PrecisionGoal goal;
  const std::optional<double> target = precision_target(s);
  if (!target) return goal;
  goal.target = *target;
  char mesh_source[80];
  std::snprintf(mesh_source, sizeof mesh_source, "mesh: %g h_min of the finest clustered grid",
                kTargetFineCells);
  goal.target_source = s.granular.target_from_mesh ? mesh_source : "granular.target_half_width";
  goal.measure = [s](const scene::Lattice& fields, const std::vector<scene::Lattice>& groups) {
    granular::PrecisionMeasure m;
    shockfit::ShockResult r = shockfit::locate_shock(s, fields);
    shockfit::apply_group_interval(s, groups, r);
    m.half_width = shock_position_half_width(s, r);
    if (r.shock == scene::ShockKind::detached) {
      m.value = r.standoff;
      m.value_to_position = 1.0;
    } else if (r.shock == scene::ShockKind::attached && std::isfinite(m.half_width) &&
               r.shock_angle_ci_deg > 0) {
      m.value = r.shock_angle_deg;
      m.value_to_position =
          attached_reach(s, r) * scene::kDeg;  // the half-width's lever, per degree
    }
    m.quantity = r.shock == scene::ShockKind::attached   ? "shock_angle"
                 : r.shock == scene::ShockKind::detached ? "standoff"
                                                         : "none";
    m.details = {{"shock", scene::to_string(r.shock)},
                 {"shock_angle_deg", json_number(r.shock_angle_deg)},
                 {"shock_angle_ci_deg", json_number(r.shock_angle_ci_deg)},
                 {"standoff", json_number(r.standoff)},
                 {"standoff_ci", json_number(r.standoff_ci)},
                 {"interval_method", r.interval_method}};
    return m;
  };
  return goal;
}

}  // namespace pipeline
