#include "scene/body_traits.hpp"

#include <algorithm>

#include "scene/body.hpp"
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

}  // namespace scene
