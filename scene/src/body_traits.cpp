#include "scene/body_traits.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace scene {

std::optional<double> attached_shock_beta(const BodySpec& b, double mach, double gamma) {
  switch (b.kind) {
    case BodyKind::wedge:
      return oblique_shock_beta(mach, b.angle_deg * kDeg, gamma);
    case BodyKind::disc:
    case BodyKind::apollo:
    case BodyKind::polygon:
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<double> attached_shock_beta(const Scene& s) {
  if (!s.body) return std::nullopt;
  return attached_shock_beta(*s.body, s.freestream.mach, s.freestream.gamma);
}

bool reference_is_exact_oblique_shock(const Scene& s) {
  return attached_shock_beta(s).has_value();
}

double band_anisotropy(const Scene& s) {
  if (s.mesh.anisotropy) return *s.mesh.anisotropy;
  return attached_shock_beta(s) ? kStraightShockAnisotropy : 1.0;
}

bool shock_may_stand_off(const Scene& s) {
  return s.body.has_value() && !attached_shock_beta(s).has_value();
}

std::optional<double> straight_ramp_length(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::wedge:
      return b.length;
    case BodyKind::disc:
    case BodyKind::apollo:
    case BodyKind::polygon:
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<double> calibration_angle_deg(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::wedge:
      return b.angle_deg;
    case BodyKind::disc:
    case BodyKind::apollo:
    case BodyKind::polygon:
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string> bow_shape_class(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::disc:
      return "disc";
    case BodyKind::apollo:
      return "apollo";
    case BodyKind::wedge:
    case BodyKind::polygon:
      return std::nullopt;
  }
  return std::nullopt;
}

double correlation_nose_radius(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::disc:
      return b.radius;
    case BodyKind::wedge:
    case BodyKind::apollo:
    case BodyKind::polygon: {
      const auto g = make_body(b);
      double lo = g.polyline.front().y, hi = lo;
      for (const auto& p : g.polyline) {
        lo = std::min(lo, p.y);
        hi = std::max(hi, p.y);
      }
      return 0.5 * (hi - lo);
    }
  }
  return 0.0;
}

bool correlation_is_exact_shape(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::disc:
      return true;
    case BodyKind::wedge:
    case BodyKind::apollo:
    case BodyKind::polygon:
      return false;
  }
  return false;
}

namespace {
// Nose (most upstream x) and widest station (x of the largest |y|) of a body.
struct Stations {
  double x_nose, x_widest;
};
Stations stations(const BodyGeometry& g) {
  Stations st{g.polyline.front().x, g.polyline.front().x};
  double widest = 0;
  for (const Vec2 p : g.polyline) {
    st.x_nose = std::min(st.x_nose, p.x);
    if (std::abs(p.y) > widest) {
      widest = std::abs(p.y);
      st.x_widest = p.x;
    }
  }
  return st;
}

// Whether the body's widest station is a sharp corner that the flow behind
// a detached shock reaches only at sonic speed: a wedge's base corner.
// Polygons: not claimed. A pointed polygon nose can carry an attached shock
// and a supersonic flow to its corners (an arrow at Mach 3 with its barbs on
// the outflow boundary: treated as subsonic it ended 10 flow-throughs
// unsteady, as supersonic it was steady at 9.2).
bool sharp_shoulder(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::wedge:
      return true;
    case BodyKind::polygon:
    case BodyKind::disc:
    case BodyKind::apollo:
      return false;
  }
  return false;
}
}  // namespace

bool starts_at_rest(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::wedge:
      return false;
    case BodyKind::disc:
    case BodyKind::apollo:
    case BodyKind::polygon:
      return true;
  }
  return true;
}

double post_shock_mach_at_outflow(const Scene& s) {
  if (!s.body) throw InputError(s.source_file + ": scene has no body, so no outflow");
  const double mach = s.freestream.mach, gamma = s.freestream.gamma;
  if (const auto beta = attached_shock_beta(s))
    return oblique_downstream_mach(mach, *beta, s.body->angle_deg * kDeg, gamma);
  const Stations st = stations(make_body(*s.body));
  const double x_out = std::min(st.x_widest, scene_domain(s).xmax);
  const double radius = correlation_nose_radius(*s.body);
  const double vertex = st.x_nose - billig_standoff_cylinder(mach) * radius;
  const double rc = billig_shock_radius_cylinder(mach) * radius;
  const double y = billig_shock_y(mach, radius, x_out - vertex);
  // Billig's hyperbola: dx/dy = (y/Rc) / sqrt(1 + (y tan(mu)/Rc)^2); the
  // shock's angle to the stream is atan(dy/dx) (normal at the vertex).
  const double tan_mu = std::tan(std::asin(1.0 / mach));
  const double dx_dy = (y / rc) / std::sqrt(1.0 + std::pow(y * tan_mu / rc, 2));
  const double sigma = std::atan2(1.0, dx_dy);
  return oblique_downstream_mach(mach, sigma, oblique_deflection(mach, sigma, gamma), gamma);
}

bool outflow_can_be_subsonic(const Scene& s) {
  if (post_shock_mach_at_outflow(s) < 1.0) return true;
  if (attached_shock_beta(s) || !sharp_shoulder(*s.body)) return false;
  // A detached shock ahead of a body whose sharp shoulder lies on the outflow
  // boundary (a domain that cuts a wedge at its base; the default domain
  // keeps the base inside): the sonic line starts at the boundary itself, so
  // the flow leaves subsonic between the body and the shock (the Mach 2,
  // 30 deg wedge cut at its base: Mach 0.35-0.57 over the whole outflow).
  return !sharp_base_inside_domain(s);
}

bool sharp_base_inside_domain(const Scene& s) {
  if (!s.body || !sharp_shoulder(*s.body)) return false;
  // Body and domain compute the station each their own way: equal to round-off.
  constexpr double kOnBoundary = 1e-9;
  return widest_station_x(s) < scene_domain(s).xmax - kOnBoundary * body_length(*s.body);
}

double widest_station_x(const Scene& s) {
  if (!s.body) throw std::logic_error("widest_station_x: a scene without a body");
  return stations(make_body(*s.body)).x_widest;
}

}  // namespace scene
