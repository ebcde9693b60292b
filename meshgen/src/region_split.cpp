#include "region_split.hpp"

#include <algorithm>
#include <cmath>

namespace meshgen {

using scene::Vec2;

namespace {

// Size samples per side of the domain for the cell-count balance.
constexpr int kBalanceLattice = 200;
// Cuts tried, as fractions of the estimated cells left of the cut: the
// balanced one first, then further off.
constexpr double kCutFractions[] = {0.5, 0.45, 0.55, 0.4, 0.6, 0.35, 0.65};
// A cut keeps this far (domain widths) from any curve's end point, so no
// sliver segment or near-tangent crossing reaches gmsh.
constexpr double kEndClearance = 1e-3;

// x where the cumulative estimated cell count reaches each fraction.
std::vector<double> balanced_cuts(const FluidRegion& region,
                                  const std::function<double(Vec2)>& size) {
  const scene::Domain& d = region.domain;
  const double dx = d.width() / kBalanceLattice, dy = d.height() / kBalanceLattice;
  std::vector<double> column(kBalanceLattice, 0.0);
  double total = 0.0;
  for (int i = 0; i < kBalanceLattice; ++i)
    for (int j = 0; j < kBalanceLattice; ++j) {
      const Vec2 p{d.xmin + (i + 0.5) * dx, d.ymin + (j + 0.5) * dy};
      if (!region.contains(p)) continue;
      const double h = size(p);
      column[static_cast<std::size_t>(i)] += 1.0 / (h * h);
    }
  for (const double c : column) total += c;
  std::vector<double> out;
  if (!(total > 0.0) || !std::isfinite(total)) return out;
  for (const double f : kCutFractions) {
    double sum = 0.0;
    for (int i = 0; i < kBalanceLattice; ++i) {
      const double c = column[static_cast<std::size_t>(i)];
      if (sum + c >= f * total) {
        out.push_back(d.xmin + (i + (f * total - sum) / c) * dx);
        break;
      }
      sum += c;
    }
  }
  return out;
}

double min_x(const BoundaryCurve& c) {
  return std::min(c.a.x, c.b.x);
}
double max_x(const BoundaryCurve& c) {
  return std::max(c.a.x, c.b.x);
}

// An arc's x-extent (its chord's, widened by the radius when it may bulge
// past either end: conservative).
std::pair<double, double> x_extent(const BoundaryCurve& c) {
  if (!c.is_arc) return {min_x(c), max_x(c)};
  const double r = scene::norm(c.a - c.center);
  return {std::min(min_x(c), c.center.x - r), std::max(max_x(c), c.center.x + r)};
}

std::optional<RegionPieces> split_at(const FluidRegion& region, double x, double clearance) {
  const std::vector<BoundaryCurve>& outer = region.loops.front();
  std::vector<std::size_t> crossed;
  std::vector<Vec2> at;
  for (std::size_t k = 0; k < outer.size(); ++k) {
    const BoundaryCurve& c = outer[k];
    const auto [lo, hi] = x_extent(c);
    if (hi < x - clearance || lo > x + clearance) continue;
    if (c.is_arc || std::abs(c.a.x - x) <= clearance || std::abs(c.b.x - x) <= clearance)
      return std::nullopt;
    const double t = (x - c.a.x) / (c.b.x - c.a.x);
    crossed.push_back(k);
    at.push_back({x, c.a.y + t * (c.b.y - c.a.y)});
  }
  if (crossed.size() != 2) return std::nullopt;
  for (std::size_t h = 1; h < region.loops.size(); ++h)
    for (const BoundaryCurve& c : region.loops[h]) {
      const auto [lo, hi] = x_extent(c);
      if (lo <= x + clearance && hi >= x - clearance) return std::nullopt;
    }
  // Walking the outer loop counter-clockwise: from the first crossing to
  // the second is one piece, closed by the cut back; the rest is the other.
  const std::size_t i = crossed[0], j = crossed[1];
  const Vec2 p = at[0], q = at[1];
  const auto part = [](const BoundaryCurve& c, Vec2 a, Vec2 b) {
    BoundaryCurve out = c;
    out.a = a;
    out.b = b;
    return PieceCurve{out, false};
  };
  const auto cut = [](Vec2 a, Vec2 b) {
    return PieceCurve{BoundaryCurve{false, a, b, {}, true, Patch::body}, true};
  };
  std::vector<PieceCurve> first{part(outer[i], p, outer[i].b)};
  for (std::size_t k = i + 1; k < j; ++k) first.push_back({outer[k], false});
  first.push_back(part(outer[j], outer[j].a, q));
  first.push_back(cut(q, p));
  std::vector<PieceCurve> second{part(outer[j], q, outer[j].b)};
  for (std::size_t k = j + 1; k < outer.size(); ++k) second.push_back({outer[k], false});
  for (std::size_t k = 0; k < i; ++k) second.push_back({outer[k], false});
  second.push_back(part(outer[i], outer[i].a, p));
  second.push_back(cut(p, q));
  // Which side `first` lies on: its curves other than the cut.
  double sx = 0.0;
  for (std::size_t k = 0; k + 1 < first.size(); ++k) sx += first[k].curve.a.x + first[k].curve.b.x;
  const bool first_left = sx / (2.0 * static_cast<double>(first.size() - 1)) < x;
  RegionPieces r;
  r.x = x;
  r.loops[first_left ? 0 : 1].push_back(std::move(first));
  r.loops[first_left ? 1 : 0].push_back(std::move(second));
  for (std::size_t h = 1; h < region.loops.size(); ++h) {
    std::vector<PieceCurve> hole;
    for (const BoundaryCurve& c : region.loops[h]) hole.push_back({c, false});
    r.loops[x_extent(region.loops[h].front()).first < x ? 0 : 1].push_back(std::move(hole));
  }
  return r;
}

}  // namespace

std::optional<RegionPieces> split_region(const FluidRegion& region,
                                         const std::function<double(Vec2)>& size) {
  if (region.loops.empty()) return std::nullopt;
  const double clearance = kEndClearance * region.domain.width();
  for (const double x : balanced_cuts(region, size))
    if (auto r = split_at(region, x, clearance)) return r;
  return std::nullopt;
}

}  // namespace meshgen
