#include "scene/body.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/units.hpp"

namespace scene {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;

constexpr double kPi = std::numbers::pi;
// Relative edge length below which an edge counts as zero-length.
constexpr double kZeroEdge = 1e-12;
// Apollo command module proportions (fractions of the maximum diameter D),
// from the Apollo CM outer mould line: heat-shield spherical radius 4.694 m,
// shoulder (toroidal) radius 0.196 m, afterbody cone half-angle 33 deg,
// height 3.23 m, for D = 3.912 m. The cone is closed by a flat top.
constexpr double kApolloShieldRadius = 1.2;
constexpr double kApolloShoulderRadius = 0.05;
constexpr double kApolloConeHalfAngleDeg = 33.0;
constexpr double kApolloHeight = 0.826;

Polygon to_cgal(const std::vector<Vec2>& pts) {
  Polygon p;
  for (const Vec2 q : pts) p.push_back(Kernel::Point_2(q.x, q.y));
  return p;
}

std::string pt(Vec2 p) {
  std::ostringstream os;
  os << "(" << p.x << ", " << p.y << ")";
  return os.str();
}

// Appends the polyline of an arc (excluding its start point) so that the
// sagitta of every chord is at most `tol`.
void append_arc(std::vector<Vec2>& out, const BodyPiece& a, double tol) {
  const double r = a.radius;
  double t0 = std::atan2(a.a.y - a.center.y, a.a.x - a.center.x);
  double t1 = std::atan2(a.b.y - a.center.y, a.b.x - a.center.x);
  if (a.ccw) { while (t1 <= t0) t1 += 2 * kPi; } else { while (t1 >= t0) t1 -= 2 * kPi; }
  const double max_step = 2.0 * std::acos(std::max(-1.0, 1.0 - tol / r));
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(t1 - t0) / max_step)));
  for (int k = 1; k < n; ++k) {
    const double t = t0 + (t1 - t0) * k / n;
    out.push_back({a.center.x + r * std::cos(t), a.center.y + r * std::sin(t)});
  }
  out.push_back(a.b);
}

BodyPiece line(Vec2 a, Vec2 b) { return {BodyPiece::Kind::line, a, b, {}, 0.0, true}; }
BodyPiece arc(Vec2 a, Vec2 b, Vec2 c, bool ccw) {
  return {BodyPiece::Kind::arc, a, b, c, norm(a - c), ccw};
}
Vec2 on_circle(Vec2 c, double r, double deg) {
  return {c.x + r * std::cos(deg * kDeg), c.y + r * std::sin(deg * kDeg)};
}

std::vector<BodyPiece> apollo_pieces(double D) {
  const double rs = kApolloShieldRadius * D, rt = kApolloShoulderRadius * D;
  const Vec2 cs{rs, 0.0};
  const double yc = 0.5 * D - rt;
  const double xc = rs - std::sqrt((rs - rt) * (rs - rt) - yc * yc);
  const Vec2 ct{xc, yc}, ctl{xc, -yc};
  // Tangent point of shield and shoulder, on the line of their centres.
  const double shield_deg = std::atan2(yc, xc - rs) / kDeg;   // about 157 deg
  const double cone = kApolloConeHalfAngleDeg;
  const Vec2 t_up = on_circle(cs, rs, shield_deg), t_lo = {t_up.x, -t_up.y};
  const Vec2 c_up = on_circle(ct, rt, 90.0 - cone), c_lo = {c_up.x, -c_up.y};
  const double xr = kApolloHeight * D;
  const double yr = c_up.y - (xr - c_up.x) * std::tan(cone * kDeg);
  const Vec2 r_up{xr, yr}, r_lo{xr, -yr};
  const Vec2 nose{0.0, 0.0};
  return {arc(nose, t_lo, cs, true),    arc(t_lo, c_lo, ctl, true), line(c_lo, r_lo),
          line(r_lo, r_up),             line(r_up, c_up),           arc(c_up, t_up, ct, true),
          arc(t_up, nose, cs, true)};
}

double seg_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / norm2(ab), 0.0, 1.0);
  return norm(p - (a + t * ab));
}

bool is_mirror_symmetric(const std::vector<Vec2>& poly, double scale) {
  // Every vertex must have a mirror image among the vertices.
  const double tol = 1e-9 * scale;
  for (const Vec2 p : poly) {
    const bool found = std::any_of(poly.begin(), poly.end(), [&](Vec2 q) {
      return std::abs(q.x - p.x) <= tol && std::abs(q.y + p.y) <= tol;
    });
    if (!found) return false;
  }
  return true;
}

}  // namespace

std::vector<Vec2> validated_polygon(const std::vector<Vec2>& raw) {
  std::vector<Vec2> pts = raw;
  if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();  // explicit closing point
  if (pts.size() < 3)
    throw InputError("polygon needs at least 3 distinct points, got " + std::to_string(pts.size()));
  double scale = 0.0;
  for (const Vec2 p : pts) scale = std::max({scale, std::abs(p.x), std::abs(p.y)});
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 a = pts[i], b = pts[(i + 1) % pts.size()];
    if (norm(b - a) <= kZeroEdge * scale)
      throw InputError("zero-length edge " + std::to_string(i) + " at " + pt(a));
  }
  Polygon poly = to_cgal(pts);
  // Zero area first: CGAL calls a collinear polygon non-simple, which would
  // hide the more useful message.
  if (std::abs(CGAL::to_double(poly.area())) <= kZeroEdge * scale * scale)
    throw InputError("polygon has zero area");
  if (!poly.is_simple()) {
    // Name the first pair of crossing edges for the user.
    const std::size_t n = pts.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j) {
        if (i == 0 && j == n - 1) continue;
        const Kernel::Segment_2 s1(poly[i], poly[(i + 1) % n]), s2(poly[j], poly[(j + 1) % n]);
        if (CGAL::do_intersect(s1, s2))
          throw InputError("polygon is self-intersecting: edge " + std::to_string(i) + " " +
                           pt(pts[i]) + "-" + pt(pts[(i + 1) % n]) + " crosses edge " +
                           std::to_string(j) + " " + pt(pts[j]) + "-" + pt(pts[(j + 1) % n]));
      }
    throw InputError("polygon is not simple (repeated or collinear overlapping edges)");
  }
  if (poly.orientation() == CGAL::COLLINEAR) throw InputError("polygon has zero area");
  if (poly.orientation() == CGAL::CLOCKWISE) std::reverse(pts.begin(), pts.end());
  return pts;
}

BodyGeometry make_body(const BodySpec& spec) {
  BodyGeometry g;
  switch (spec.kind) {
    case BodyKind::wedge: {
      const double th = spec.angle_deg * kDeg, L = spec.length;
      const Vec2 apex{0, 0}, lo{L * std::cos(th), -L * std::sin(th)}, up{lo.x, -lo.y};
      g.pieces = {line(apex, lo), line(lo, up), line(up, apex)};
      break;
    }
    case BodyKind::disc: {
      const double r = spec.radius;
      g.pieces = {arc({-r, 0}, {r, 0}, {0, 0}, true), arc({r, 0}, {-r, 0}, {0, 0}, true)};
      break;
    }
    case BodyKind::apollo:
      g.pieces = apollo_pieces(spec.diameter);
      break;
    case BodyKind::polygon: {
      const std::vector<Vec2> pts = validated_polygon(spec.points);
      for (std::size_t i = 0; i < pts.size(); ++i) g.pieces.push_back(line(pts[i], pts[(i + 1) % pts.size()]));
      break;
    }
  }
  g.length = body_length(spec);
  const double tol = spec.curve_tolerance * g.length;
  g.polyline.push_back(g.pieces.front().a);
  for (const BodyPiece& p : g.pieces) {
    if (p.kind == BodyPiece::Kind::line) g.polyline.push_back(p.b);
    else append_arc(g.polyline, p, tol);
  }
  g.polyline.pop_back();  // closing point repeats the first
  if (spec.kind != BodyKind::polygon) g.polyline = validated_polygon(g.polyline);
  g.symmetric = is_mirror_symmetric(g.polyline, g.length);
  if (g.symmetric) {
    // Nose: the most upstream point ON the symmetry line (a notch facing the
    // stream has its most upstream vertices off the axis). Where an edge
    // crosses the axis without a vertex there, insert one so that walks
    // from the nose split the outline into its mirror halves.
    std::size_t best = g.polyline.size();
    double best_x = std::numeric_limits<double>::infinity();
    Vec2 best_p{};
    const std::size_t n = g.polyline.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 a = g.polyline[i], b = g.polyline[(i + 1) % n];
      if (a.y == 0.0 && a.x < best_x) { best = n; best_x = a.x; best_p = a; }
      if ((a.y < 0.0 && b.y > 0.0) || (a.y > 0.0 && b.y < 0.0)) {
        const Vec2 c = a + (a.y / (a.y - b.y)) * (b - a);
        if (c.x < best_x) { best = i; best_x = c.x; best_p = {c.x, 0.0}; }
      }
    }
    if (best < n) g.polyline.insert(g.polyline.begin() + static_cast<std::ptrdiff_t>(best + 1), best_p);
    g.nose = best_p;
  } else {
    // Nose: the most upstream vertex.
    Vec2 nose = g.polyline.front();
    for (const Vec2 p : g.polyline)
      if (p.x < nose.x || (p.x == nose.x && std::abs(p.y) < std::abs(nose.y))) nose = p;
    g.nose = nose;
  }
  return g;
}

bool point_in_body(const BodyGeometry& g, Vec2 p) {
  // Polygon_2::bounded_side is O(n); bodies have at most a few thousand edges.
  const Polygon poly = to_cgal(g.polyline);
  return poly.bounded_side(Kernel::Point_2(p.x, p.y)) != CGAL::ON_UNBOUNDED_SIDE;
}

double widest_section_x(const BodyGeometry& g) {
  Vec2 widest = g.polyline.front();
  for (const auto& v : g.polyline)
    if (std::abs(v.y) > std::abs(widest.y) || (std::abs(v.y) == std::abs(widest.y) && v.x < widest.x))
      widest = v;
  return widest.x;
}

double signed_distance(const BodyGeometry& g, Vec2 p) {
  double d = std::numeric_limits<double>::infinity();
  const std::size_t n = g.polyline.size();
  for (std::size_t i = 0; i < n; ++i) d = std::min(d, seg_distance(p, g.polyline[i], g.polyline[(i + 1) % n]));
  return point_in_body(g, p) ? -d : d;
}

Vec2 edge_normal(const BodyGeometry& g, std::size_t i) {
  const std::size_t n = g.polyline.size();
  const Vec2 t = normalized(g.polyline[(i + 1) % n] - g.polyline[i % n]);
  return {t.y, -t.x};
}

std::vector<Station> surface_stations(const BodyGeometry& g, int count) {
  const auto& P = g.polyline;
  const std::size_t n = P.size();
  std::size_t inose = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (P[i] == g.nose) inose = i;
  // Clockwise from the nose runs over the upper surface (CCW outline). Keep
  // the contiguous run of upstream-facing edges (outward normal against the flow).
  auto walk = [&](bool clockwise) {
    std::vector<Vec2> chain{P[inose]};
    std::vector<Vec2> normals;
    std::size_t i = inose;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = clockwise ? (i + n - 1) % n : (i + 1) % n;
      const Vec2 nrm = clockwise ? edge_normal(g, j) : edge_normal(g, i);
      if (nrm.x >= 0.0) break;
      chain.push_back(P[j]);
      normals.push_back(nrm);
      i = j;
    }
    return std::make_pair(chain, normals);
  };
  auto [up, nup] = walk(true);
  std::vector<Vec2> chain;
  std::vector<Vec2> normals;
  if (g.symmetric) {
    chain = up;
    normals = nup;
  } else {
    auto [lo, nlo] = walk(false);
    chain.assign(lo.rbegin(), lo.rend());
    normals.assign(nlo.rbegin(), nlo.rend());
    chain.insert(chain.end(), up.begin() + 1, up.end());
    normals.insert(normals.end(), nup.begin(), nup.end());
  }
  std::vector<double> s(chain.size(), 0.0);
  for (std::size_t k = 1; k < chain.size(); ++k) s[k] = s[k - 1] + norm(chain[k] - chain[k - 1]);
  std::vector<Station> out;
  if (chain.size() < 2 || count < 1) return out;
  const double total = s.back();
  const double s_nose = g.symmetric ? 0.0 : s[chain.size() - up.size()];
  for (int k = 0; k < count; ++k) {
    const double sk = count == 1 ? 0.0 : total * k / (count - 1);
    std::size_t e = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), sk) - s.begin());
    e = std::clamp<std::size_t>(e, 1, chain.size() - 1) - 1;  // edge e: chain[e] -> chain[e+1]
    const double f = (sk - s[e]) / std::max(s[e + 1] - s[e], 1e-300);
    Station st;
    st.point = chain[e] + f * (chain[e + 1] - chain[e]);
    // At a vertex (f at 0 or 1) take the mean of the adjacent edge normals.
    Vec2 nrm = normals[e];
    constexpr double kAtVertex = 1e-9;
    if (f < kAtVertex && e > 0) nrm = normalized(normals[e - 1] + normals[e]);
    if (f > 1 - kAtVertex && e + 1 < normals.size()) nrm = normalized(normals[e] + normals[e + 1]);
    if (g.symmetric && k == 0) nrm = {-1.0, 0.0};  // on the symmetry line
    st.normal = nrm;
    st.s = sk - s_nose;
    out.push_back(st);
  }
  return out;
}

std::vector<Vec2> clipped_outline(const BodyGeometry& g, const Domain& d) {
  // Walk from the nose along the outline and keep what lies strictly inside
  // the domain; the walk ends where the outline first reaches a boundary
  // (cut exactly there). Clockwise from the nose is the upper surface.
  const auto& P = g.polyline;
  const std::size_t n = P.size();
  std::size_t inose = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (P[i] == g.nose) inose = i;
  auto inside = [&](Vec2 p) { return p.x < d.xmax && p.x > d.xmin && p.y > d.ymin && p.y < d.ymax; };
  auto walk = [&](bool clockwise, bool& closed) {
    std::vector<Vec2> out{P[inose]};
    std::size_t i = inose;
    closed = false;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = clockwise ? (i + n - 1) % n : (i + 1) % n;
      const Vec2 a = P[i], b = P[j];
      if (inside(b)) {
        out.push_back(b);
        i = j;
        if (j == inose) { closed = true; break; }
        continue;
      }
      double t = 1.0;
      if (b.x >= d.xmax) t = std::min(t, (d.xmax - a.x) / (b.x - a.x));
      if (b.y <= d.ymin) t = std::min(t, (d.ymin - a.y) / (b.y - a.y));
      if (b.y >= d.ymax) t = std::min(t, (d.ymax - a.y) / (b.y - a.y));
      if (b.x <= d.xmin) t = std::min(t, (d.xmin - a.x) / (b.x - a.x));
      out.push_back(a + t * (b - a));
      break;
    }
    return out;
  };
  bool closed = false;
  std::vector<Vec2> upper = walk(true, closed);
  if (closed || d.symmetric) return upper;
  std::vector<Vec2> lower = walk(false, closed);
  std::vector<Vec2> out(lower.rbegin(), lower.rend());
  out.insert(out.end(), upper.begin() + 1, upper.end());
  return out;
}

}  // namespace scene
