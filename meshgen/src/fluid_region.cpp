#include "meshgen/fluid_region.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "scene/errors.hpp"
#include "scene/units.hpp"

namespace meshgen {

using scene::BodyPiece;
using scene::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;
// Relative distance (in body lengths) under which two points coincide.
constexpr double kCoincide = 1e-10;
// Samples per body piece when looking for where it leaves the domain; the
// crossing is then found by bisection to round-off.
constexpr int kWalkSamples = 256;
constexpr int kBisections = 60;
// A crossing this close (relative) to a piece's end point is that end point.
constexpr double kSnapToVertex = 1e-8;
// A fluid corner narrower than this between the body and a boundary makes a
// cusp no valid cell fits in (the disc's rear point on x = xmax).
constexpr double kMinCornerDeg = 5.0;
// Arcs are handed to gmsh in pieces of at most a quarter turn.
constexpr double kMaxArcSweep = 0.5 * kPi;

double sweep(const BodyPiece& p) {
  const double t0 = std::atan2(p.a.y - p.center.y, p.a.x - p.center.x);
  double t1 = std::atan2(p.b.y - p.center.y, p.b.x - p.center.x);
  if (p.ccw) { while (t1 <= t0) t1 += 2 * kPi; } else { while (t1 >= t0) t1 -= 2 * kPi; }
  return t1 - t0;
}

Vec2 point_at(const BodyPiece& p, double t) {
  if (p.kind == BodyPiece::Kind::line) return p.a + t * (p.b - p.a);
  const double t0 = std::atan2(p.a.y - p.center.y, p.a.x - p.center.x) + t * sweep(p);
  return {p.center.x + p.radius * std::cos(t0), p.center.y + p.radius * std::sin(t0)};
}

// Unit tangent in the direction of travel at parameter t.
Vec2 tangent_at(const BodyPiece& p, double t) {
  if (p.kind == BodyPiece::Kind::line) return scene::normalized(p.b - p.a);
  const Vec2 r = scene::normalized(point_at(p, t) - p.center);
  return p.ccw ? scene::perp(r) : -scene::perp(r);
}

BodyPiece reversed(BodyPiece p) {
  std::swap(p.a, p.b);
  p.ccw = !p.ccw;
  return p;
}

std::pair<BodyPiece, BodyPiece> split(const BodyPiece& p, double t) {
  BodyPiece first = p, second = p;
  first.b = second.a = point_at(p, t);
  return {first, second};
}

// Parameter of a point known to lie on the piece, or nullopt if it does not.
std::optional<double> param_of(const BodyPiece& p, Vec2 q, double eps) {
  if (p.kind == BodyPiece::Kind::line) {
    const Vec2 d = p.b - p.a;
    const double t = scene::dot(q - p.a, d) / scene::norm2(d);
    if (t < 0 || t > 1 || scene::norm(p.a + t * d - q) > eps) return std::nullopt;
    return t;
  }
  if (std::abs(scene::norm(q - p.center) - p.radius) > eps) return std::nullopt;
  BodyPiece part = p;
  part.b = q;
  const double t = sweep(part) / sweep(p);
  if (t < 0 || t > 1) return std::nullopt;
  return t;
}

struct Walk {
  std::vector<BodyPiece> pieces;
  bool closed = false;   // went all the way round inside the domain
  Vec2 exit_tangent;     // direction of travel where it left
};

class Rect {
 public:
  Rect(const scene::Domain& d, double eps, double scale) : d_(d), eps_(eps), scale_(scale) {}
  double scale() const { return scale_; }
  bool inside(Vec2 p) const {
    return p.x > d_.xmin + eps_ && p.x < d_.xmax - eps_ && p.y > d_.ymin + eps_ && p.y < d_.ymax - eps_;
  }
  // Moves a point just outside (or on) the rectangle onto the side it crossed.
  Vec2 snap(Vec2 p) const {
    if (p.x >= d_.xmax - eps_) p.x = d_.xmax;
    else if (p.y >= d_.ymax - eps_) p.y = d_.ymax;
    else if (p.x <= d_.xmin + eps_) p.x = d_.xmin;
    else if (p.y <= d_.ymin + eps_) p.y = d_.ymin;
    return p;
  }
  // Side a boundary point lies on (a corner counts as bottom or outlet).
  Patch side(Vec2 p) const {
    if (std::abs(p.y - d_.ymin) <= eps_) return Patch::bottom;
    if (std::abs(p.x - d_.xmax) <= eps_) return Patch::outlet;
    if (std::abs(p.y - d_.ymax) <= eps_) return Patch::top;
    return Patch::inlet;
  }
  double perimeter_position(Vec2 p) const {
    const double w = d_.width(), h = d_.height();
    switch (side(p)) {
      case Patch::bottom: return p.x - d_.xmin;
      case Patch::outlet: return w + p.y - d_.ymin;
      case Patch::top: return w + h + d_.xmax - p.x;
      default: return 2 * w + h + d_.ymax - p.y;
    }
  }
  // Boundary segments from e counter-clockwise round to s.
  std::vector<BoundaryCurve> path(Vec2 e, Vec2 s) const {
    const double w = d_.width(), h = d_.height(), per = 2 * (w + h);
    const double pe = perimeter_position(e);
    double ps = perimeter_position(s);
    if (ps <= pe + eps_) ps += per;
    const Vec2 corners[4] = {{d_.xmin, d_.ymin}, {d_.xmax, d_.ymin}, {d_.xmax, d_.ymax}, {d_.xmin, d_.ymax}};
    const double pos[4] = {0, w, w + h, 2 * w + h};
    std::vector<Vec2> pts{e};
    for (int lap = 0; lap < 2; ++lap)
      for (int k = 0; k < 4; ++k) {
        const double pc = pos[k] + lap * per;
        if (pc > pe + eps_ && pc < ps - eps_) pts.push_back(corners[k]);
      }
    pts.push_back(s);
    std::vector<BoundaryCurve> out;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      if (scene::norm(pts[i + 1] - pts[i]) <= eps_) continue;
      BoundaryCurve c;
      c.a = pts[i];
      c.b = pts[i + 1];
      c.patch = side(0.5 * (c.a + c.b));
      out.push_back(c);
    }
    return out;
  }

 private:
  scene::Domain d_;
  double eps_, scale_;
};

// Follows the pieces (starting at the nose) while they stay inside the
// rectangle and cuts the first one that leaves it exactly at the crossing.
Walk walk(const std::vector<BodyPiece>& pieces, const Rect& rect) {
  Walk w;
  for (const BodyPiece& p : pieces) {
    double t_in = 0.0;
    std::optional<double> t_out;
    for (int k = 1; k <= kWalkSamples; ++k) {
      const double t = static_cast<double>(k) / kWalkSamples;
      if (rect.inside(point_at(p, t))) { t_in = t; continue; }
      t_out = t;
      break;
    }
    if (!t_out) { w.pieces.push_back(p); continue; }
    double lo = t_in, hi = *t_out;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      (rect.inside(point_at(p, mid)) ? lo : hi) = mid;
    }
    // A piece that ends on the boundary (the wedge's rear corner) keeps its
    // exact end point instead of the bisection's, which stops eps short.
    BodyPiece cut = scene::norm(point_at(p, hi) - p.b) <= kSnapToVertex * rect.scale() ? p : split(p, hi).first;
    cut.b = rect.snap(cut.b);
    w.exit_tangent = tangent_at(p, hi);
    if (scene::norm(cut.b - cut.a) > 0) w.pieces.push_back(cut);
    return w;
  }
  w.closed = true;
  return w;
}

std::vector<BoundaryCurve> to_curves(const std::vector<BodyPiece>& pieces) {
  std::vector<BoundaryCurve> out;
  for (const BodyPiece& p : pieces) {
    if (p.kind == BodyPiece::Kind::line) {
      out.push_back({false, p.a, p.b, {}, true, Patch::body});
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep(p)) / kMaxArcSweep - 1e-9)));
    for (int k = 0; k < n; ++k) {
      const Vec2 a = k == 0 ? p.a : point_at(p, static_cast<double>(k) / n);
      const Vec2 b = k == n - 1 ? p.b : point_at(p, static_cast<double>(k + 1) / n);
      out.push_back({true, a, b, p.center, p.ccw, Patch::body});
    }
  }
  return out;
}

double corner_deg(Vec2 u, Vec2 v) {
  return std::acos(std::clamp(scene::dot(u, v), -1.0, 1.0)) / scene::kDeg;
}

}  // namespace

std::string patch_name(Patch p) {
  switch (p) {
    case Patch::inlet: return "inlet";
    case Patch::outlet: return "outlet";
    case Patch::top: return "top";
    case Patch::bottom: return "bottom";
    case Patch::body: return "body";
  }
  return "body";
}

std::vector<Vec2> sample_curve(const BoundaryCurve& c, double sag) {
  if (!c.is_arc) return {c.a, c.b};
  BodyPiece p{BodyPiece::Kind::arc, c.a, c.b, c.center, scene::norm(c.a - c.center), c.ccw};
  const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - sag / p.radius));
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(sweep(p)) / step)));
  std::vector<Vec2> out;
  for (int k = 0; k <= n; ++k) out.push_back(k == n ? c.b : point_at(p, static_cast<double>(k) / n));
  return out;
}

bool inside_polygon(const std::vector<Vec2>& poly, Vec2 p) {
  int winding = 0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n];
    const double side = scene::cross(b - a, p - a);
    if (a.y <= p.y) {
      if (b.y > p.y && side > 0) ++winding;
    } else if (b.y <= p.y && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

bool FluidRegion::contains(Vec2 p) const {
  return p.x > domain.xmin && p.x < domain.xmax && p.y > domain.ymin && p.y < domain.ymax &&
         !inside_polygon(body.polyline, p);
}

double FluidRegion::area() const {
  double a = 0.0;
  for (const auto& loop : loops) {
    std::vector<Vec2> pts;
    for (const BoundaryCurve& c : loop) {
      const std::vector<Vec2> s = sample_curve(c, 1e-6 * length_scale);
      pts.insert(pts.end(), s.begin(), s.end() - 1);
    }
    double signed_area = 0.0;
    for (std::size_t i = 0; i < pts.size(); ++i) signed_area += scene::cross(pts[i], pts[(i + 1) % pts.size()]);
    a += 0.5 * signed_area;  // holes run clockwise, so they subtract
  }
  return a;
}

FluidRegion make_fluid_region(const scene::Scene& s) {
  if (!s.body) throw scene::InputError(s.source_file + ": scene has no body; meshgen grids the flow round a body");
  FluidRegion r;
  r.body = scene::make_body(*s.body);
  r.scene_domain = r.domain = scene::scene_domain(s);
  r.length_scale = r.body.length;
  const double eps = kCoincide * r.length_scale;

  // Clockwise pieces (fluid on the left of travel, like the outer loop),
  // starting at the nose; a piece through the nose is split there.
  std::vector<BodyPiece> cw;
  for (auto it = r.body.pieces.rbegin(); it != r.body.pieces.rend(); ++it) cw.push_back(reversed(*it));
  std::size_t start = cw.size();
  for (std::size_t i = 0; i < cw.size() && start == cw.size(); ++i) {
    if (scene::norm(cw[i].a - r.body.nose) <= eps) { start = i; break; }
    const auto t = param_of(cw[i], r.body.nose, eps);
    if (t && *t > 0 && *t < 1) {
      const auto [first, second] = split(cw[i], *t);
      cw[i] = second;
      cw.insert(cw.begin() + static_cast<std::ptrdiff_t>(i), first);
      start = i + 1;
    }
  }
  if (start == cw.size()) start = 0;
  std::rotate(cw.begin(), cw.begin() + static_cast<std::ptrdiff_t>(start), cw.end());
  std::vector<BodyPiece> ccw;  // from the nose the other way (lower surface)
  for (auto it = cw.rbegin(); it != cw.rend(); ++it) ccw.push_back(reversed(*it));

  const auto build = [&](const scene::Domain& d, bool& grazing) {
    const Rect rect(d, eps, r.length_scale);
    grazing = false;
    std::vector<std::vector<BoundaryCurve>> loops;
    const Walk upper = walk(cw, rect);
    if (upper.closed) {
      loops.push_back(rect.path({d.xmin, d.ymin}, {d.xmin, d.ymin}));
      loops.push_back(to_curves(upper.pieces));
      return loops;
    }
    const Vec2 exit = upper.pieces.back().b;
    std::vector<BodyPiece> body = upper.pieces;
    Vec2 entry = r.body.nose;
    if (!d.symmetric) {
      const Walk lower = walk(ccw, rect);
      std::vector<BodyPiece> lo;
      for (auto it = lower.pieces.rbegin(); it != lower.pieces.rend(); ++it) lo.push_back(reversed(*it));
      entry = lo.front().a;
      lo.insert(lo.end(), body.begin(), body.end());
      body = lo;
    }
    std::vector<BoundaryCurve> loop = to_curves(body);
    const std::vector<BoundaryCurve> rest = rect.path(exit, entry);
    if (!rest.empty()) {
      // Corners where the body meets the boundary, measured with the
      // boundary segments actually used (a corner point belongs to two sides).
      if (corner_deg(-upper.exit_tangent, scene::normalized(rest.front().b - rest.front().a)) < kMinCornerDeg)
        grazing = true;
      const Vec2 t_in = tangent_at(body.front(), 0.0);
      if (!d.symmetric && corner_deg(scene::normalized(rest.back().a - rest.back().b), t_in) < kMinCornerDeg)
        grazing = true;
    }
    loop.insert(loop.end(), rest.begin(), rest.end());
    loops.push_back(loop);
    return loops;
  };

  bool grazing = false;
  r.loops = build(r.domain, grazing);
  if (grazing) {
    // Thickest station: the highest point of the outline.
    double x_top = r.body.polyline.front().x, y_top = r.body.polyline.front().y;
    for (const Vec2 p : r.body.polyline)
      if (p.y > y_top) { y_top = p.y; x_top = p.x; }
    for (const BodyPiece& p : r.body.pieces)
      if (p.kind == BodyPiece::Kind::arc && p.center.y + p.radius >= y_top &&
          param_of(p, p.center + Vec2{0, p.radius}, eps)) {
        y_top = p.center.y + p.radius;
        x_top = p.center.x;
      }
    r.domain.xmax = x_top;
    r.outlet_moved = true;
    r.loops = build(r.domain, grazing);
    if (grazing)
      throw scene::InputError(s.source_file + ": domain: the body meets the outflow boundary at a grazing "
                              "angle (below " + std::to_string(kMinCornerDeg) + " deg); set domain.xmax");
  }
  return r;
}

}  // namespace meshgen
