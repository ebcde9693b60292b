#include "meshgen/shock_extension.hpp"

#include <algorithm>
#include <cmath>

namespace meshgen {

using scene::Vec2;

namespace {

// The end tangent is fitted over this fraction of the curve's length, and
// over at least two points.
constexpr double kEndStretch = 0.25;
// The exit along the tangent is bracketed by steps of this fraction of the
// domain's diagonal, then bisected to kExitBisections halvings.
constexpr double kExitStep = 1.0 / 2000.0;
constexpr int kExitBisections = 50;
// An end is carried at most this many end-stretch lengths: farther, a bow
// shock's wing bends (towards the Mach angle) by more than the data fitted
// can tell, and its band would be a guess.
constexpr double kMaxExtrapolation = 1.0;

struct Stretch {
  Vec2 direction;       // unit, pointing out of the curve's end
  std::size_t far = 0;  // index of the stretch's other end
  double length = 0.0;
  double curvature = 0.0;  // |turn| between the stretch's two halves over half its length
};

// Least-squares direction (principal axis) of points [lo, hi], oriented from
// `from` towards `to`.
Vec2 principal_direction(const std::vector<Vec2>& pts, std::size_t lo, std::size_t hi, Vec2 from,
                         Vec2 to) {
  Vec2 mean{0, 0};
  for (std::size_t i = lo; i <= hi; ++i) mean += pts[i];
  mean = mean / static_cast<double>(hi - lo + 1);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = lo; i <= hi; ++i) {
    const Vec2 d = pts[i] - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  Vec2 dir{std::cos(angle), std::sin(angle)};
  if (scene::dot(dir, to - from) < 0) dir = -dir;
  return dir;
}

// The stretch at the last point (at_end) or the first.
Stretch end_stretch(const std::vector<Vec2>& pts, bool at_end) {
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) total += scene::norm(pts[i + 1] - pts[i]);
  const std::size_t n = pts.size();
  const auto at = [&](std::size_t k) { return at_end ? pts[n - 1 - k] : pts[k]; };
  std::size_t k = 1;
  double len = scene::norm(at(1) - at(0));
  while (k + 1 < n && len < kEndStretch * total) {
    len += scene::norm(at(k + 1) - at(k));
    ++k;
  }
  Stretch s;
  s.length = len;
  s.far = at_end ? n - 1 - k : k;
  const std::size_t lo = std::min(s.far, at_end ? n - 1 : std::size_t{0});
  const std::size_t hi = std::max(s.far, at_end ? n - 1 : std::size_t{0});
  s.direction = principal_direction(pts, lo, hi, at(k), at(0));
  // Curvature from the turn between the halves' directions, when each half
  // has at least two points.
  if (hi - lo >= 3) {
    const std::size_t mid = lo + (hi - lo) / 2;
    const Vec2 d1 = principal_direction(pts, lo, mid, pts[lo], pts[mid]);
    const Vec2 d2 = principal_direction(pts, mid, hi, pts[mid], pts[hi]);
    const double turn = std::atan2(std::abs(d1.x * d2.y - d1.y * d2.x), scene::dot(d1, d2));
    s.curvature = turn / (0.5 * len);
  }
  return s;
}

// Distance along `dir` from `p` (inside) to where the line first leaves the region.
double exit_distance(const FluidRegion& region, Vec2 p, Vec2 dir) {
  const scene::Domain& d = region.domain;
  const double diagonal = std::hypot(d.width(), d.height());
  const double step = kExitStep * diagonal;
  double inside = 0.0;
  for (double t = step; t <= 2.0 * diagonal; t += step) {
    if (!region.contains(p + t * dir)) {
      double lo = inside, hi = t;
      for (int it = 0; it < kExitBisections; ++it) {
        const double mid = 0.5 * (lo + hi);
        (region.contains(p + mid * dir) ? lo : hi) = mid;
      }
      return lo;
    }
    inside = t;
  }
  return inside;
}

}  // namespace

ExtendedShock extend_shock_to_boundary(const std::vector<Vec2>& curve,
                                       const std::vector<double>& ci, const FluidRegion& region) {
  ExtendedShock out{curve, ci, 0.0, 0.0};
  // The distinct points in order, each with the index of its last copy in
  // `curve` (copies share a position, and the last copy's ci stands).
  std::vector<Vec2> pts;
  std::vector<std::size_t> last;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (pts.empty() || !(pts.back() == curve[i])) {
      pts.push_back(curve[i]);
      last.push_back(i);
    }
    last.back() = i;
  }
  if (pts.size() < 2) return out;
  const bool has_ci = !ci.empty() && ci.size() == curve.size();
  const auto ci_of = [&](std::size_t k) { return std::isfinite(ci[last[k]]) ? ci[last[k]] : 0.0; };
  for (const bool at_end : {false, true}) {
    const std::size_t tip_index = at_end ? pts.size() - 1 : 0;
    const Vec2 tip = pts[tip_index];
    if (!region.contains(tip)) continue;
    const Stretch s = end_stretch(pts, at_end);
    const double length =
        std::min(exit_distance(region, tip, s.direction), kMaxExtrapolation * s.length);
    if (!(length > 0.0)) continue;
    const Vec2 exit = tip + length * s.direction;
    // The straight line's own 95% spread, plus where the curve would have
    // gone had it kept bending as over its end stretch.
    double w_exit = 0.5 * s.curvature * length * (length + s.length);
    if (has_ci) {
      const double spread = (ci_of(tip_index) + ci_of(s.far)) / s.length;
      w_exit += ci_of(tip_index) + length * spread;
    }
    if (at_end) {
      out.curve.push_back(exit);
      if (has_ci) out.ci.push_back(w_exit);
      out.end_length = length;
    } else {
      out.curve.insert(out.curve.begin(), exit);
      if (has_ci) out.ci.insert(out.ci.begin(), w_exit);
      out.start_length = length;
    }
  }
  return out;
}

}  // namespace meshgen
