#include "scene/body_traits.hpp"

#include <algorithm>
#include <numbers>

#include "scene/body.hpp"
#include "scene/gasdynamics.hpp"

namespace scene {

std::optional<double> attached_shock_beta(const Scene& s) {
  if (!s.body) return std::nullopt;
  switch (s.body->kind) {
    case BodyKind::wedge:
      return oblique_shock_beta(s.freestream.mach, s.body->angle_deg * std::numbers::pi / 180.0, s.freestream.gamma);
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
