#include "band_strip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshgen {

using scene::Vec2;

namespace {

// A cell may turn the shock by at most kCurvatureCells radians (~6 deg):
// neighbouring columns then meet at that angle at most, which is what the
// strip adds to the grid's non-orthogonality.
constexpr double kCurvatureCells = 0.1;
// Neighbouring along-shock lengths differ by at most this factor.
constexpr double kAlongGrowth = 1.2;
// Rows beyond the band grow by kGrowthRows until one reaches l / kEdgeJump:
// the isotropic grid outside (cells of size l at the outline) then meets a
// row at most kEdgeJump times thinner.
constexpr double kGrowthRows = 2.0;
constexpr double kEdgeJump = 2.5;
// A strip keeps this many h_min clear of the region's boundary and of other strips.
constexpr double kStripMargin = 1.0;
// Columns may not fold: the strip's half-width stays below this fraction of
// the radius of curvature.
constexpr double kMaxWidthCurvature = 0.5;
// A strip's rows span the widest band half-width w along it, so a run whose
// w varies (a wedge's ci grows with the distance from the apex) is split
// into strips whose w varies by at most this factor: narrow strips near
// the apex fit closer to it, and rows never thin below h_min.
constexpr double kMaxWidthRatio = 2.0;
// Consecutive strips of one run are this many h_min apart; the isotropic
// h_min band fills the gap.
constexpr double kStripGap = 2.0;
// Every corner of a strip's quads turns the same way, at an angle whose sine
// is at least this (30 to 150 deg): a noisy curve's normals can swing enough
// between stations to fold the outer rows even where its smoothed curvature
// passes, and gmsh would mesh round a self-overlapping strip.
constexpr double kMinCornerSine = 0.5;
// Fewer stations than this and the run stays isotropic.
constexpr std::size_t kMinStations = 3;
// A strip covering less than kFullCover of its run is tried again at
// kAspectRetry times its aspect, down to kMinStripAspect (below it a strip's
// cells are hardly longer than the isotropic band's); a retry is kept when
// it covers kRetryGain times the arc length.
constexpr double kFullCover = 0.8;
constexpr double kAspectRetry = 0.5;
constexpr double kMinStripAspect = 2.0;
constexpr double kRetryGain = 1.25;
// Boundary sampling: arcs to this sag, in h_min.
constexpr double kBoundarySag = 0.05;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Arc-length parametrised polyline.
struct Polyline {
  std::vector<Vec2> p;
  std::vector<double> s;  // cumulative length
  std::vector<double> w;  // band half-width per vertex
  explicit Polyline(const ShockRun& r) : p(r.points), w(r.half_width) {
    s.assign(p.size(), 0.0);
    for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + scene::norm(p[i] - p[i - 1]);
  }
  double length() const { return s.back(); }
  std::size_t segment(double t) const {
    const auto it = std::upper_bound(s.begin(), s.end(), t);
    const std::size_t k = it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1;
    return std::min(k, p.size() - 2);
  }
  Vec2 at(double t) const {
    t = std::clamp(t, 0.0, length());
    const std::size_t k = segment(t);
    const double len = s[k + 1] - s[k];
    const double f = len > 0 ? (t - s[k]) / len : 0.0;
    return p[k] + f * (p[k + 1] - p[k]);
  }
  double width(double t) const {
    t = std::clamp(t, 0.0, length());
    const std::size_t k = segment(t);
    const double len = s[k + 1] - s[k];
    const double f = len > 0 ? (t - s[k]) / len : 0.0;
    return w[k] + f * (w[k + 1] - w[k]);
  }
  // Unit tangent from the chord over [t - half, t + half] (clamped to the ends).
  Vec2 tangent(double t, double half) const {
    const Vec2 a = at(t - half), b = at(t + half);
    return scene::normalized(b - a);
  }
  // Curvature: the turn between the chord tangents at t - half and t + half
  // (each `half` long), over the distance between the chords' centres.
  double curvature(double t, double half) const {
    const auto chord = [&](double c) {
      // Chords stay whole: their centres are kept half a chord inside the run.
      const double q = std::min(0.5 * half, 0.5 * length());
      c = std::clamp(c, q, length() - q);
      return std::pair{scene::normalized(at(c + q) - at(c - q)), c};
    };
    const auto [ta, ca] = chord(t - half);
    const auto [tb, cb] = chord(t + half);
    if (cb - ca <= 0) return 0.0;
    return std::atan2(std::abs(scene::cross(ta, tb)), scene::dot(ta, tb)) / (cb - ca);
  }
  // The piece [a, b] as a run.
  ShockRun piece(double a, double b) const {
    ShockRun r;
    r.points.push_back(at(a));
    r.half_width.push_back(width(a));
    for (std::size_t i = 0; i < p.size(); ++i)
      if (s[i] > a && s[i] < b) {
        r.points.push_back(p[i]);
        r.half_width.push_back(w[i]);
      }
    r.points.push_back(at(b));
    r.half_width.push_back(width(b));
    return r;
  }
};

// Row offsets: the band in equal rows of at most h_min, then growth rows out
// to l / kEdgeJump, mirrored.
std::vector<double> make_rows(double w_max, double h_min, double l_max) {
  const int n = std::max(1, static_cast<int>(std::ceil(w_max / h_min - 1e-9)));
  std::vector<double> half{0.0};
  for (int k = 1; k <= n; ++k) half.push_back(w_max * k / n);
  double t = w_max / n;
  while (t * kEdgeJump < l_max) {
    t *= kGrowthRows;
    half.push_back(half.back() + t);
  }
  std::vector<double> rows;
  for (auto it = half.rbegin(); it != half.rend(); ++it) rows.push_back(-*it);
  for (std::size_t k = 1; k < half.size(); ++k) rows.push_back(half[k]);
  return rows;
}

// Arc-length intervals of `line` over which its half-width varies by at most
// kMaxWidthRatio, `gap` apart, covering the run from end to end.
std::vector<std::pair<double, double>> width_pieces(const Polyline& line, double gap) {
  std::vector<std::pair<double, double>> out;
  double t0 = 0.0;
  while (t0 < line.length()) {
    double lo = line.width(t0), hi = lo, end = line.length();
    for (std::size_t i = 0; i < line.p.size(); ++i) {
      if (line.s[i] <= t0) continue;
      lo = std::min(lo, line.w[i]);
      hi = std::max(hi, line.w[i]);
      if (hi > kMaxWidthRatio * lo) {
        // End at the previous vertex, or at this one if none lies inside.
        end = i > 0 && line.s[i - 1] > t0 ? line.s[i - 1] : line.s[i];
        break;
      }
    }
    out.emplace_back(t0, end);
    t0 = end + gap;
  }
  return out;
}

// Distance between segments ab and cd (zero when they cross).
double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const auto side = [](Vec2 o, Vec2 p, Vec2 q) { return scene::cross(p - o, q - o); };
  if (side(c, d, a) * side(c, d, b) < 0 && side(a, b, c) * side(a, b, d) < 0) return 0.0;
  const auto to_segment = [](Vec2 p, Vec2 s, Vec2 e) {
    const Vec2 se = e - s;
    const double len2 = scene::dot(se, se);
    const double f = len2 > 0 ? std::clamp(scene::dot(p - s, se) / len2, 0.0, 1.0) : 0.0;
    return scene::norm(p - (s + f * se));
  };
  return std::min(
      {to_segment(a, c, d), to_segment(b, c, d), to_segment(c, a, b), to_segment(d, a, b)});
}

// What a strip's outline must keep clear of, tested exactly on segments: the
// region's boundary (its curves sampled to a sag) and the outlines of the
// strips already placed. Sampling points along a column is not enough: two
// strips of one run whose end columns tilt towards each other cross between
// samples, and gmsh then splits the crossing lines, which a transfinite
// strip cannot survive.
class Obstacles {
 public:
  Obstacles(const FluidRegion& region, double sag) {
    for (const auto& loop : region.loops) {
      std::vector<Vec2> pts;
      for (const BoundaryCurve& c : loop) {
        const std::vector<Vec2> s = sample_curve(c, sag);
        pts.insert(pts.end(), s.begin(), s.end());
      }
      add_loop(pts);
    }
  }
  void add_strip(const std::vector<Vec2>& outline) {
    add_loop(outline);
    strips_.push_back(outline);
  }
  // Whether segment ab stays `margin` away from every obstacle and neither
  // end lies inside a placed strip (a strip wholly inside another crosses
  // nothing).
  bool clear(Vec2 a, Vec2 b, double margin) const {
    const Vec2 lo{std::min(a.x, b.x) - margin, std::min(a.y, b.y) - margin};
    const Vec2 hi{std::max(a.x, b.x) + margin, std::max(a.y, b.y) + margin};
    for (const Seg& s : segs_) {
      if (s.hi.x < lo.x || s.lo.x > hi.x || s.hi.y < lo.y || s.lo.y > hi.y) continue;
      if (segment_distance(a, b, s.a, s.b) < margin) return false;
    }
    for (const auto& poly : strips_)
      if (inside_polygon(poly, a) || inside_polygon(poly, b)) return false;
    return true;
  }

 private:
  struct Seg {
    Vec2 a, b, lo, hi;
  };
  void add_loop(const std::vector<Vec2>& pts) {
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Vec2 a = pts[k], b = pts[(k + 1) % pts.size()];
      segs_.push_back({a,
                       b,
                       {std::min(a.x, b.x), std::min(a.y, b.y)},
                       {std::max(a.x, b.x), std::max(a.y, b.y)}});
    }
  }
  std::vector<Seg> segs_;
  std::vector<std::vector<Vec2>> strips_;
};

// Stations along one run: positions in arc length.
std::vector<double> station_positions(const Polyline& line, const StripRule& rule) {
  const double l_max = rule.max_aspect * rule.h_min;
  const double window = l_max;
  std::vector<double> s{0.0};
  double prev = l_max;
  while (s.back() < line.length()) {
    const double k = line.curvature(s.back(), window);
    double l = k > 0 ? std::min(l_max, kCurvatureCells / k) : l_max;
    l = std::clamp(std::min(l, prev * kAlongGrowth), rule.h_min, l_max);
    s.push_back(s.back() + l);
    prev = l;
  }
  // Stretch to end exactly on the run's end (the last step shrinks or the
  // whole sequence scales by less than one step's worth).
  if (s.size() < 2) return s;
  const double f = line.length() / s.back();
  for (double& v : s) v *= f;
  return s;
}

// Whether column i lies in the region, clear of the obstacles.
bool column_fits(const ShockStrip& strip, std::size_t i, const FluidRegion& region,
                 const Obstacles& obstacles, double margin) {
  const Vec2 a = strip.node(i, 0), b = strip.node(i, strip.rows.size() - 1);
  return region.contains(a) && obstacles.clear(a, b, margin);
}

// Whether the strip's two long sides between columns i and i + 1 are clear.
bool sides_fit(const ShockStrip& strip, std::size_t i, const Obstacles& obstacles, double margin) {
  const std::size_t top = strip.rows.size() - 1;
  return obstacles.clear(strip.node(i, 0), strip.node(i + 1, 0), margin) &&
         obstacles.clear(strip.node(i, top), strip.node(i + 1, top), margin);
}

// Whether the quads between columns i and i + 1 are sound: convex, turning
// the way (along, normal) does, no corner sharper than kMinCornerSine allows.
bool quads_sound(const ShockStrip& strip, std::size_t i) {
  for (std::size_t j = 0; j + 1 < strip.rows.size(); ++j) {
    const Vec2 q[4] = {strip.node(i, j), strip.node(i + 1, j), strip.node(i + 1, j + 1),
                       strip.node(i, j + 1)};
    for (int k = 0; k < 4; ++k) {
      const Vec2 e1 = q[(k + 1) % 4] - q[k], e2 = q[(k + 2) % 4] - q[(k + 1) % 4];
      if (scene::cross(e1, e2) < kMinCornerSine * scene::norm(e1) * scene::norm(e2)) return false;
    }
  }
  return true;
}

// The longest run of consecutive fitting stations whose neighbours are
// joined by sound quads (joined[i]: stations i and i + 1): [first, last).
std::pair<std::size_t, std::size_t> longest_fit(const std::vector<bool>& ok,
                                                const std::vector<bool>& joined) {
  std::size_t best_a = 0, best_n = 0;
  for (std::size_t i = 0; i < ok.size();) {
    if (!ok[i]) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < ok.size() && ok[j] && joined[j - 1]) ++j;
    if (j - i > best_n) {
      best_n = j - i;
      best_a = i;
    }
    i = j;
  }
  return {best_a, best_a + best_n};  // half-open
}

// The strip along `line` at rule r: its longest part whose columns fit
// (none if fewer than kMinStations do), and the arc length it covers.
struct Candidate {
  ShockStrip strip;
  double from = 0.0, to = 0.0;  // arc length along the run
  bool at_start = false, at_end = false;
  double covered() const { return strip.stations() > 0 ? to - from : 0.0; }
};

Candidate fit_strip(const Polyline& line, const StripRule& r, const FluidRegion& region,
                    const Obstacles& obstacles, double margin) {
  const double l_max = r.max_aspect * r.h_min;
  // One half-width for the whole strip, the run's widest: scaling the rows
  // with the local ci would thin them below h_min where the ci narrows
  // (near a wedge's apex), and the thinnest row sets the time step.
  const double w_max = *std::max_element(line.w.begin(), line.w.end());
  ShockStrip strip;
  const std::vector<double> s = station_positions(line, r);
  // Growth rows end at the longest cell this strip has, not at a h_min.
  double l_run = r.h_min;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) l_run = std::max(l_run, s[i + 1] - s[i]);
  strip.rows = make_rows(std::max(w_max, r.h_min), r.h_min, l_run);
  const double half_width = strip.rows.back();
  for (const double t : s) {
    strip.centre.push_back(line.at(t));
    strip.normal.push_back(scene::perp(line.tangent(t, 0.5 * l_max)));
  }
  std::vector<bool> ok(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    ok[i] = line.curvature(s[i], l_max) * half_width <= kMaxWidthCurvature &&
            column_fits(strip, i, region, obstacles, margin);
  std::vector<bool> joined(s.size(), false);
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
    joined[i] = quads_sound(strip, i) && sides_fit(strip, i, obstacles, margin);
  const auto [a, b] = longest_fit(ok, joined);
  Candidate c;
  if (b - a < kMinStations) return c;
  c.strip.rows = strip.rows;
  for (std::size_t i = a; i < b; ++i) {
    c.strip.centre.push_back(strip.centre[i]);
    c.strip.normal.push_back(strip.normal[i]);
    if (i + 1 < b) c.strip.along.push_back(s[i + 1] - s[i]);
  }
  c.from = s[a];
  c.to = s[b - 1];
  c.at_start = a == 0;
  c.at_end = b == s.size();
  return c;
}

}  // namespace

std::vector<Vec2> ShockStrip::outline() const {
  std::vector<Vec2> out;
  const std::size_t n = stations(), m = rows.size();
  for (std::size_t i = 0; i < n; ++i) out.push_back(node(i, 0));
  for (std::size_t j = 1; j < m; ++j) out.push_back(node(n - 1, j));
  for (std::size_t i = n - 1; i-- > 0;) out.push_back(node(i, m - 1));
  for (std::size_t j = m - 1; j-- > 1;) out.push_back(node(0, j));
  return out;
}

BandLayout layout_strips(const std::vector<ShockRun>& runs, const FluidRegion& region,
                         const StripRule& rule) {
  BandLayout out;
  const double margin = kStripMargin * rule.h_min;
  Obstacles obstacles(region, kBoundarySag * rule.h_min);
  // A strip's growth rows reach out to its longest cell, so on a coarse
  // grid of a small domain they cross the body or the domain's edge and
  // few columns fit (or none: a coarse grid without its strip can then have
  // more cells than a finer one with it). When the full aspect covers less
  // than kFullCover of the run, shorter cells (fewer growth rows) are tried,
  // each kept only if it covers kRetryGain times more.
  const auto lay = [&](const ShockRun& run) {
    const Polyline line(run);
    Candidate best = fit_strip(line, rule, region, obstacles, margin);
    for (StripRule r = rule; best.covered() < kFullCover * line.length();) {
      r.max_aspect *= kAspectRetry;
      if (r.max_aspect < kMinStripAspect) break;
      Candidate c = fit_strip(line, r, region, obstacles, margin);
      if (c.covered() > kRetryGain * best.covered()) best = std::move(c);
    }
    if (best.strip.stations() == 0) {
      out.uncovered.push_back(run);
      return;
    }
    if (!best.at_start) out.uncovered.push_back(line.piece(0.0, best.from));
    if (!best.at_end) out.uncovered.push_back(line.piece(best.to, line.length()));
    obstacles.add_strip(best.strip.outline());
    out.strips.push_back(std::move(best.strip));
  };
  for (const ShockRun& run : runs) {
    if (run.points.size() < 2) {
      out.uncovered.push_back(run);
      continue;
    }
    const Polyline line(run);
    double covered = 0.0;
    for (const auto& [a, b] : width_pieces(line, kStripGap * rule.h_min)) {
      if (a > covered) out.uncovered.push_back(line.piece(covered, a));
      lay(line.piece(a, b));
      covered = b;
    }
  }
  return out;
}

BandSize::BandSize(const SizeParams& p, const BandLayout& layout,
                   const std::vector<Vec2>& body_polyline)
    : base_(p, layout.uncovered, body_polyline), slope_(p.growth - 1.0), h_max_(p.h_max) {
  // SegmentIndex gives min(d - v); with v = -l_edge / slope that is
  // (min(l_edge + slope d)) / slope.
  for (const ShockStrip& st : layout.strips) {
    std::vector<Vec2> loop = st.outline();
    const std::size_t n = st.stations(), m = st.rows.size();
    std::vector<double> v;
    const auto side = [&](std::size_t i) {
      const double lo = i > 0 ? st.along[i - 1] : st.along[0];
      const double hi = i + 1 < n ? st.along[i] : st.along[n - 2];
      return 0.5 * (lo + hi);
    };
    const auto row = [&](std::size_t j) {
      const std::size_t k = j == 0 ? 0 : j - 1;
      return st.rows[k + 1] - st.rows[k];
    };
    for (std::size_t i = 0; i < n; ++i) v.push_back(side(i));
    for (std::size_t j = 1; j < m; ++j) v.push_back(j + 1 == m ? side(n - 1) : row(j));
    for (std::size_t i = n - 1; i-- > 0;) v.push_back(side(i));
    for (std::size_t j = m - 1; j-- > 1;) v.push_back(row(j));
    loop.push_back(loop.front());
    v.push_back(v.front());
    for (double& x : v) x = -x / slope_;
    edges_.add_polyline(loop, v);
  }
  edges_.build(p.h_max / slope_);
}

StripGridCount count_cells(const BandLayout& layout, const BandSize& size,
                           const FluidRegion& region) {
  StripGridCount c;
  std::vector<std::vector<Vec2>> outlines;
  for (const ShockStrip& st : layout.strips) {
    c.strip_cells += static_cast<double>(st.cells());
    outlines.push_back(st.outline());
  }
  c.unstructured = estimate_cells([&size](Vec2 p) { return size(p); }, region, outlines);
  return c;
}

double BandSize::operator()(Vec2 p) const {
  const double h = base_(p);
  const double e = edges_.excess(p);
  return std::isfinite(e) ? std::min({h, slope_ * e, h_max_}) : h;
}

BandShapeMeter::BandShapeMeter(const std::vector<ShockRun>& runs) {
  for (const ShockRun& r : runs)
    for (std::size_t i = 0; i + 1 < r.points.size(); ++i)
      segs_.emplace_back(r.points[i], r.points[i + 1]);
}

Vec2 BandShapeMeter::normal_near(Vec2 p) const {
  double best = kInf;
  Vec2 n{0.0, 1.0};
  for (const auto& [a, b] : segs_) {
    const Vec2 ab = b - a;
    const double len2 = scene::norm2(ab);
    if (len2 <= 0) continue;
    const double t = std::clamp(scene::dot(p - a, ab) / len2, 0.0, 1.0);
    const double d = scene::norm2(p - (a + t * ab));
    if (d < best) {
      best = d;
      n = scene::perp(ab / std::sqrt(len2));
    }
  }
  return n;
}

void BandShapeMeter::add(const std::vector<Vec2>& corners) {
  Vec2 c;
  for (const Vec2 q : corners) c += q;
  c = c / static_cast<double>(corners.size());
  const Vec2 n = normal_near(c), t = scene::perp(n);
  double n_lo = kInf, n_hi = -kInf, t_lo = kInf, t_hi = -kInf;
  for (const Vec2 q : corners) {
    n_lo = std::min(n_lo, scene::dot(q, n));
    n_hi = std::max(n_hi, scene::dot(q, n));
    t_lo = std::min(t_lo, scene::dot(q, t));
    t_hi = std::max(t_hi, scene::dot(q, t));
  }
  const double across = n_hi - n_lo, along = t_hi - t_lo;
  const double aspect = std::max(across, along) / std::max(std::min(across, along), 1e-300);
  ++s_.cells;
  sum_ += aspect;
  s_.max_aspect = std::max(s_.max_aspect, aspect);
  s_.max_thickness = std::max(s_.max_thickness, across);
}

BandShape BandShapeMeter::result() const {
  BandShape r = s_;
  r.mean_aspect = s_.cells ? sum_ / static_cast<double>(s_.cells) : 0.0;
  return r;
}

}  // namespace meshgen
