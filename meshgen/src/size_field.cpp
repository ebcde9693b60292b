#include "meshgen/size_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshgen {

using scene::Vec2;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Lattice points per side for cell-count estimates (the estimate is only a
// starting point; the mesher's count is what is checked).
constexpr int kEstimateLattice = 400;
constexpr double kMaxBuckets = 256.0;
}  // namespace

std::vector<ShockRun> clip_shock(const std::vector<Vec2>& curve, const std::vector<double>& half_width,
                                 const FluidRegion& region, double resolution) {
  std::vector<ShockRun> runs;
  ShockRun cur;
  const auto flush = [&] {
    if (!cur.points.empty()) runs.push_back(cur);
    cur = {};
  };
  const auto add = [&](Vec2 p, double w) {
    if (!cur.points.empty() && cur.points.back() == p) return;
    cur.points.push_back(p);
    cur.half_width.push_back(w);
  };
  const auto width = [&](std::size_t i) { return i < half_width.size() ? half_width[i] : 0.0; };
  if (curve.size() == 1) {
    if (region.contains(curve[0])) add(curve[0], width(0));
    flush();
    return runs;
  }
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const Vec2 a = curve[i], b = curve[i + 1];
    const double wa = width(i), wb = width(i + 1);
    // Walk the segment in steps no longer than `resolution`; each change of
    // side is located by bisection.
    const int n = std::max(1, static_cast<int>(std::ceil(scene::norm(b - a) / resolution)));
    double t_prev = 0.0;
    bool in_prev = region.contains(a);
    if (in_prev) add(a, wa);
    for (int k = 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      const bool in = region.contains(a + t * (b - a));
      if (in != in_prev) {
        double lo = t_prev, hi = t;
        for (int it = 0; it < 50; ++it) {
          const double mid = 0.5 * (lo + hi);
          (region.contains(a + mid * (b - a)) == in_prev ? lo : hi) = mid;
        }
        const double tc = in_prev ? lo : hi;  // the crossing, on the inside
        add(a + tc * (b - a), wa + tc * (wb - wa));
        if (in_prev) flush();
      }
      in_prev = in;
      t_prev = t;
    }
    if (in_prev) add(b, wb);
  }
  flush();
  return runs;
}

void SegmentIndex::add_polyline(const std::vector<Vec2>& pts, const std::vector<double>& values) {
  const auto v = [&](std::size_t i) { return i < values.size() ? values[i] : 0.0; };
  if (pts.size() == 1) segs_.push_back({pts[0], pts[0], v(0), v(0)});
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) segs_.push_back({pts[i], pts[i + 1], v(i), v(i + 1)});
}

void SegmentIndex::build(double cutoff) {
  cutoff_ = cutoff;
  if (segs_.empty()) return;
  double xmin = kInf, ymin = kInf, xmax = -kInf, ymax = -kInf, vmax = 0.0;
  for (const Seg& s : segs_) {
    xmin = std::min({xmin, s.a.x, s.b.x});
    xmax = std::max({xmax, s.a.x, s.b.x});
    ymin = std::min({ymin, s.a.y, s.b.y});
    ymax = std::max({ymax, s.a.y, s.b.y});
    vmax = std::max({vmax, s.va, s.vb});
  }
  // Every segment that can matter lies within cutoff + vmax: with cells that
  // wide, the 3 x 3 block round a point holds all of them.
  // Never more than kMaxBuckets per side (a zero cut-off, h_min = h_max,
  // would otherwise ask for a lattice of zero-width cells).
  const double extent = std::max(xmax - xmin, ymax - ymin);
  cell_ = std::max({cutoff + vmax, extent / kMaxBuckets, 1e-300});
  x0_ = xmin;
  y0_ = ymin;
  nx_ = static_cast<int>((xmax - xmin) / cell_) + 1;
  ny_ = static_cast<int>((ymax - ymin) / cell_) + 1;
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (std::size_t k = 0; k < segs_.size(); ++k) {
    const Seg& s = segs_[k];
    const int i0 = static_cast<int>((std::min(s.a.x, s.b.x) - x0_) / cell_);
    const int i1 = static_cast<int>((std::max(s.a.x, s.b.x) - x0_) / cell_);
    const int j0 = static_cast<int>((std::min(s.a.y, s.b.y) - y0_) / cell_);
    const int j1 = static_cast<int>((std::max(s.a.y, s.b.y) - y0_) / cell_);
    for (int j = j0; j <= std::min(j1, ny_ - 1); ++j)
      for (int i = i0; i <= std::min(i1, nx_ - 1); ++i)
        cells_[static_cast<std::size_t>(j) * nx_ + i].push_back(static_cast<int>(k));
  }
}

double SegmentIndex::excess(Vec2 p) const {
  if (segs_.empty()) return kInf;
  const int ic = static_cast<int>(std::floor((p.x - x0_) / cell_));
  const int jc = static_cast<int>(std::floor((p.y - y0_) / cell_));
  double best = kInf;
  for (int j = std::max(jc - 1, 0); j <= std::min(jc + 1, ny_ - 1); ++j)
    for (int i = std::max(ic - 1, 0); i <= std::min(ic + 1, nx_ - 1); ++i)
      for (const int k : cells_[static_cast<std::size_t>(j) * nx_ + i]) {
        const Seg& s = segs_[static_cast<std::size_t>(k)];
        const Vec2 ab = s.b - s.a;
        const double len2 = scene::norm2(ab);
        const double t = len2 > 0 ? std::clamp(scene::dot(p - s.a, ab) / len2, 0.0, 1.0) : 0.0;
        const double d = scene::norm(p - (s.a + t * ab)) - (s.va + t * (s.vb - s.va));
        best = std::min(best, d);
      }
  return best > cutoff_ ? kInf : best;
}

SizeField::SizeField(double h) : uniform_(true) { p_.h_min = p_.h_max = p_.h_body = h; }

SizeField::SizeField(const SizeParams& p, const std::vector<ShockRun>& shock, const std::vector<Vec2>& body)
    : uniform_(false), p_(p) {
  const double slope = p.growth - 1.0;
  for (const ShockRun& r : shock) shock_.add_polyline(r.points, r.half_width);
  shock_.build((p.h_max - p.h_min) / slope);
  std::vector<Vec2> closed = body;
  if (!closed.empty()) closed.push_back(closed.front());
  body_.add_polyline(closed, {});
  body_.build((p.h_max - p.h_body) / slope);
}

SizeField::SizeField(const SizeParams& p, std::shared_ptr<const scene::Lattice> h_lattice, double scale,
                     const std::vector<Vec2>& body)
    : uniform_(false), p_(p), lattice_(std::move(h_lattice)), lattice_values_(&lattice_->field("h")),
      lattice_scale_(scale) {
  std::vector<Vec2> closed = body;
  if (!closed.empty()) closed.push_back(closed.front());
  body_.add_polyline(closed, {});
  body_.build((p.h_max - p.h_body) / (p.growth - 1.0));
}

// Bilinear between cell centres, held at the outermost centres beyond them
// (the lattice need not reach the moved outlet); values are checked finite
// and positive when the lattice is read.
double SizeField::lattice_h(Vec2 p) const {
  const scene::Lattice& lat = *lattice_;
  const std::vector<double>& f = *lattice_values_;
  const double fx = std::clamp((p.x - lat.x0) / lat.dx - 0.5, 0.0, static_cast<double>(lat.nx - 1));
  const double fy = std::clamp((p.y - lat.y0) / lat.dy - 0.5, 0.0, static_cast<double>(lat.ny - 1));
  const int i = std::min(static_cast<int>(fx), std::max(lat.nx - 2, 0));
  const int j = std::min(static_cast<int>(fy), std::max(lat.ny - 2, 0));
  const int i1 = std::min(i + 1, lat.nx - 1), j1 = std::min(j + 1, lat.ny - 1);
  const double tx = fx - i, ty = fy - j;
  return (1 - tx) * (1 - ty) * f[lat.index(i, j)] + tx * (1 - ty) * f[lat.index(i1, j)] +
         (1 - tx) * ty * f[lat.index(i, j1)] + tx * ty * f[lat.index(i1, j1)];
}

double SizeField::operator()(Vec2 p) const {
  if (uniform_) return p_.h_min;
  const double slope = p_.growth - 1.0;
  double h = p_.h_max;
  if (lattice_) h = std::clamp(lattice_scale_ * lattice_h(p), p_.h_min, p_.h_max);
  const double e = shock_.excess(p);
  if (std::isfinite(e)) h = std::min(h, p_.h_min + slope * std::max(e, 0.0));
  const double db = body_.excess(p);
  if (std::isfinite(db)) h = std::min(h, p_.h_body + slope * std::max(db, 0.0));
  return h;
}

bool SizeField::in_band(Vec2 p) const {
  if (uniform_) return false;
  return shock_.excess(p) <= 0.0;
}

double estimate_cells(const SizeField& f, const FluidRegion& region) {
  return estimate_cells([&f](Vec2 p) { return f(p); }, region, {});
}

namespace {

// Which points of an n x n lattice of cell centres over `d` lie inside any of
// `polygons` (row-major). Scanlines through the rows' centres, each edge
// entered in the rows it crosses: a point-in-polygon test per point and
// polygon cost more than the sum itself on grids of long strips.
std::vector<char> lattice_mask(const std::vector<std::vector<Vec2>>& polygons,
                               const scene::Domain& d, int n) {
  const double dx = d.width() / n, dy = d.height() / n;
  std::vector<char> mask(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(n));
  for (const auto& poly : polygons) {
    for (auto& row : crossings) row.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
      if (a.y == b.y) continue;
      const double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
      // Rows whose centre y satisfies y0 <= y < y1 (half-open: a vertex
      // shared by two edges is counted once).
      const int j0 = std::max(0, static_cast<int>(std::ceil((y0 - d.ymin) / dy - 0.5)));
      const int j1 = std::min(n - 1, static_cast<int>(std::ceil((y1 - d.ymin) / dy - 0.5)) - 1);
      for (int j = j0; j <= j1; ++j) {
        const double y = d.ymin + (j + 0.5) * dy;
        crossings[static_cast<std::size_t>(j)].push_back(a.x +
                                                         (y - a.y) * (b.x - a.x) / (b.y - a.y));
      }
    }
    for (int j = 0; j < n; ++j) {
      auto& xs = crossings[static_cast<std::size_t>(j)];
      std::sort(xs.begin(), xs.end());
      for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
        const int i0 = std::max(0, static_cast<int>(std::ceil((xs[k] - d.xmin) / dx - 0.5)));
        const int i1 =
            std::min(n - 1, static_cast<int>(std::ceil((xs[k + 1] - d.xmin) / dx - 0.5)) - 1);
        for (int i = i0; i <= i1; ++i)
          mask[static_cast<std::size_t>(j) * static_cast<std::size_t>(n) +
               static_cast<std::size_t>(i)] = 1;
      }
    }
  }
  return mask;
}

}  // namespace

double estimate_cells(const std::function<double(Vec2)>& f, const FluidRegion& region,
                      const std::vector<std::vector<Vec2>>& holes) {
  const scene::Domain& d = region.domain;
  const double dx = d.width() / kEstimateLattice, dy = d.height() / kEstimateLattice;
  const std::vector<char> in_hole = lattice_mask(holes, d, kEstimateLattice);
  double n = 0.0;
  for (int j = 0; j < kEstimateLattice; ++j)
    for (int i = 0; i < kEstimateLattice; ++i) {
      if (in_hole[static_cast<std::size_t>(j) * kEstimateLattice + static_cast<std::size_t>(i)])
        continue;
      const Vec2 p{d.xmin + (i + 0.5) * dx, d.ymin + (j + 0.5) * dy};
      if (!region.contains(p)) continue;
      const double h = f(p);
      n += dx * dy / (h * h);
    }
  return n;
}

}  // namespace meshgen
