#include "pipeline/precision_goal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "json_fields.hpp"
#include "pipeline/cost_estimate.hpp"
#include "pipeline/predictor.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
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

namespace {

// What a check measures the shock's precision in.
enum class MeasureUnit {
  position,  // the shock position's half-width (body lengths)
  degrees,   // an attached shock's angle half-width, the quantity a band is widened by
  relative,  // a bow shock's standoff half-width over its standoff
};

// shockfit on the fields so far, its precision in `unit`.
granular::PrecisionMeasure measure_shock(const scene::Scene& s, const scene::Lattice& fields,
                                         const std::vector<scene::Lattice>& groups,
                                         MeasureUnit unit) {
  granular::PrecisionMeasure m;
  shockfit::ShockResult r = shockfit::locate_shock(s, fields);
  shockfit::apply_group_interval(s, groups, r);
  const bool attached = r.shock == scene::ShockKind::attached;
  if (unit == MeasureUnit::relative) {
    if (r.shock == scene::ShockKind::detached && r.standoff > 0 && std::isfinite(r.standoff_ci)) {
      m.half_width = r.standoff_ci / r.standoff;
      m.value = r.standoff;
      m.value_to_position = 1.0 / r.standoff;  // a move, relative to the standoff
    }
  } else if (unit == MeasureUnit::degrees) {
    if (attached && std::isfinite(r.shock_angle_ci_deg) && r.shock_angle_ci_deg > 0) {
      m.half_width = r.shock_angle_ci_deg;
      m.value = r.shock_angle_deg;
      m.value_to_position = 1.0;
    }
  } else {
    m.half_width = shock_position_half_width(s, r);
    if (r.shock == scene::ShockKind::detached) {
      m.value = r.standoff;
      m.value_to_position = 1.0;
    } else if (attached && std::isfinite(m.half_width) && r.shock_angle_ci_deg > 0) {
      m.value = r.shock_angle_deg;
      m.value_to_position =
          attached_reach(s, r) * scene::kDeg;  // the half-width's lever, per degree
    }
  }
  m.quantity = attached                                ? "shock_angle"
               : r.shock == scene::ShockKind::detached ? "standoff"
                                                       : "none";
  m.details = {{"shock", scene::to_string(r.shock)},
               {"shock_angle_deg", json_number(r.shock_angle_deg)},
               {"shock_angle_ci_deg", json_number(r.shock_angle_ci_deg)},
               {"standoff", json_number(r.standoff)},
               {"standoff_ci", json_number(r.standoff_ci)},
               {"interval_method", r.interval_method}};
  return m;
}

granular::PrecisionGoal band_goal(const scene::Scene& s, double angle_scatter_deg) {
  if (!std::isfinite(angle_scatter_deg))
    throw scene::InputError(
        s.source_file +
        ": granular.target_half_width: band needs a calibrated band (a wedge whose restitution "
        "comes from the calibration table, which gives the angle scatter the band is made of)");
  granular::PrecisionGoal goal;
  goal.target = band_target_deg(angle_scatter_deg);
  goal.unit = "deg";
  goal.min_flow_throughs = kBandMinAveraging;
  char source[160];
  std::snprintf(source, sizeof source,
                "band: the run's own interval widens the calibrated band (+-%.3g deg) by at most "
                "%g%%",
                band_angle_half_width_deg(0.0, angle_scatter_deg), 100.0 * kBandWidening);
  goal.target_source = source;
  goal.measure = [s](const scene::Lattice& fields, const std::vector<scene::Lattice>& groups) {
    return measure_shock(s, fields, groups, MeasureUnit::degrees);
  };
  // The band's cost is the clustered grids' CFD: averaging that narrows the
  // band by less than its own CPU seconds would save there is not worth it.
  goal.downstream_cpu = [s, angle_scatter_deg](double angle_deg, double half_width_deg) {
    if (!std::isfinite(half_width_deg)) return scene::kNaN;
    return clustered_finest_cpu(s, angle_deg,
                                band_angle_half_width_deg(half_width_deg, angle_scatter_deg));
  };
  return goal;
}

granular::PrecisionGoal standoff_goal(const scene::Scene& s) {
  granular::PrecisionGoal goal;
  goal.target = kStandoffTargetRelative;
  goal.unit = "relative";
  goal.min_flow_throughs = s.granular.averaging;
  char source[120];
  std::snprintf(source, sizeof source,
                "standoff: its 95%% interval at most %g%% of the standoff (none before %g "
                "flow-through times)",
                100.0 * kStandoffTargetRelative, s.granular.averaging);
  goal.target_source = source;
  goal.measure = [s](const scene::Lattice& fields, const std::vector<scene::Lattice>& groups) {
    return measure_shock(s, fields, groups, MeasureUnit::relative);
  };
  return goal;
}

}  // namespace

double band_target_deg(double angle_scatter_deg) {
  const double widened = 1.0 + kBandWidening;
  // The band of a perfectly averaged run: the table's part alone.
  return std::sqrt(widened * widened - 1.0) * band_angle_half_width_deg(0.0, angle_scatter_deg);
}

granular::PrecisionGoal precision_goal(const scene::Scene& s, double angle_scatter_deg) {
  if (s.granular.target_from_band) return band_goal(s, angle_scatter_deg);
  if (s.granular.target_from_standoff) return standoff_goal(s);
  granular::PrecisionGoal goal;
  const std::optional<double> target = precision_target(s);
  if (!target) return goal;
  goal.target = *target;
  char mesh_source[80];
  std::snprintf(mesh_source, sizeof mesh_source, "mesh: %g h_min of the finest clustered grid",
                kTargetFineCells);
  goal.target_source = s.granular.target_from_mesh ? mesh_source : "granular.target_half_width";
  goal.measure = [s](const scene::Lattice& fields, const std::vector<scene::Lattice>& groups) {
    return measure_shock(s, fields, groups, MeasureUnit::position);
  };
  return goal;
}

bool default_to_band_target(scene::Scene& s, double angle_scatter_deg) {
  scene::GranularParams& g = s.granular;
  if (!s.body || g.averaging_given || g.asks_precision() || !std::isfinite(angle_scatter_deg) ||
      !scene::attached_shock_beta(s))
    return false;
  g.target_from_band = true;
  return true;
}

bool default_to_standoff_target(scene::Scene& s) {
  scene::GranularParams& g = s.granular;
  if (!s.body || g.averaging_given || g.asks_precision() || scene::attached_shock_beta(s))
    return false;
  g.target_from_standoff = true;
  return true;
}

bool default_to_band_replicas(scene::Scene& s, double bow_relative) {
  scene::GranularParams& g = s.granular;
  if (!s.body || g.replicas_given || !std::isfinite(bow_relative) ||
      scene::attached_shock_beta(s) || g.replicas <= scene::kDefaultReplicas)
    return false;
  g.replicas = scene::kDefaultReplicas;
  return true;
}

void default_to_band_averaging(scene::Scene& s, double angle_scatter_deg, double bow_relative) {
  default_to_band_target(s, angle_scatter_deg);
  default_to_band_replicas(s, bow_relative);
}

}  // namespace pipeline
