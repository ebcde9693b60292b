#include "region_split.hpp"

#include <algorithm>
#include <cmath>

namespace meshgen {

using scene::Vec2;

namespace {

// Size samples per side of the domain for the cell-count balance.
constexpr int kBalanceLattice = 200;
// Where a balanced cut cannot go, these shifts (in fractions of the cell
// count) are tried, nearest first.
constexpr double kCutShifts[] = {0.0, -0.03, 0.03, -0.06, 0.06, -0.1, 0.1};
// A cut keeps this far (domain widths) from any curve's end point, so no
// sliver segment or near-tangent crossing reaches gmsh.
constexpr double kEndClearance = 1e-3;

// Cumulative estimated cells over the domain's columns.
class CellColumns {
 public:
  CellColumns(const FluidRegion& region, const std::function<double(Vec2)>& size) : d_(region.domain) {
    const double dx = d_.width() / kBalanceLattice, dy = d_.height() / kBalanceLattice;
    cumulative_.assign(kBalanceLattice + 1, 0.0);
    for (int i = 0; i < kBalanceLattice; ++i) {
      double column = 0.0;
      for (int j = 0; j < kBalanceLattice; ++j) {
        const Vec2 p{d_.xmin + (i + 0.5) * dx, d_.ymin + (j + 0.5) * dy};
        if (!region.contains(p)) continue;
        const double h = size(p);
        column += 1.0 / (h * h);
      }
      cumulative_[static_cast<std::size_t>(i) + 1] = cumulative_[static_cast<std::size_t>(i)] + column;
    }
  }
  bool usable() const { return cumulative_.back() > 0.0 && std::isfinite(cumulative_.back()); }
  // x left of which the fraction f of the cells lies.
  double x_at(double f) const {
    const double target = f * cumulative_.back();
    const auto it = std::lower_bound(cumulative_.begin() + 1, cumulative_.end(), target);
    const auto i = static_cast<std::size_t>(it - cumulative_.begin()) - 1;
    const double c = cumulative_[i + 1] - cumulative_[i];
    const double t = c > 0.0 ? (target - cumulative_[i]) / c : 0.5;
    return d_.xmin + (static_cast<double>(i) + t) * d_.width() / kBalanceLattice;
  }

 private:
  scene::Domain d_;
  std::vector<double> cumulative_;
};

// An arc's x-extent (its chord's, widened by the radius either way:
// conservative).
std::pair<double, double> x_extent(const BoundaryCurve& c) {
  const double lo = std::min(c.a.x, c.b.x), hi = std::max(c.a.x, c.b.x);
  if (!c.is_arc) return {lo, hi};
  const double r = scene::norm(c.a - c.center);
  return {std::min(lo, c.center.x - r), std::max(hi, c.center.x + r)};
}

using Loop = std::vector<PieceCurve>;

// The loop (counter-clockwise) cut at x into its left and right parts,
// each closed by the cut; nullopt when x crosses it other than on exactly
// two straight curves clear of their ends.
std::optional<std::pair<Loop, Loop>> cut_loop(const Loop& loop, double x, int cut, double clearance) {
  std::vector<std::size_t> crossed;
  std::vector<Vec2> at;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const BoundaryCurve& c = loop[k].curve;
    const auto [lo, hi] = x_extent(c);
    if (hi < x - clearance || lo > x + clearance) continue;
    if (c.is_arc || std::abs(c.a.x - x) <= clearance || std::abs(c.b.x - x) <= clearance) return std::nullopt;
    const double t = (x - c.a.x) / (c.b.x - c.a.x);
    crossed.push_back(k);
    at.push_back({x, c.a.y + t * (c.b.y - c.a.y)});
  }
  if (crossed.size() != 2) return std::nullopt;
  // Counter-clockwise from the first crossing to the second is one part,
  // closed by the cut back; the rest is the other.
  const std::size_t i = crossed[0], j = crossed[1];
  const Vec2 p = at[0], q = at[1];
  const auto part = [](const PieceCurve& c, Vec2 a, Vec2 b) {
    PieceCurve out = c;
    out.curve.a = a;
    out.curve.b = b;
    return out;
  };
  const auto cut_curve = [cut](Vec2 a, Vec2 b) {
    return PieceCurve{BoundaryCurve{false, a, b, {}, true, Patch::body}, cut};
  };
  Loop first{part(loop[i], p, loop[i].curve.b)};
  for (std::size_t k = i + 1; k < j; ++k) first.push_back(loop[k]);
  first.push_back(part(loop[j], loop[j].curve.a, q));
  first.push_back(cut_curve(q, p));
  Loop second{part(loop[j], q, loop[j].curve.b)};
  for (std::size_t k = j + 1; k < loop.size(); ++k) second.push_back(loop[k]);
  for (std::size_t k = 0; k < i; ++k) second.push_back(loop[k]);
  second.push_back(part(loop[i], loop[i].curve.a, p));
  second.push_back(cut_curve(p, q));
  double sx = 0.0;  // which side `first` lies on: its end points off the cut
  for (std::size_t k = 0; k + 1 < first.size(); ++k) sx += first[k].curve.a.x + first[k].curve.b.x;
  if (sx / (2.0 * static_cast<double>(first.size() - 1)) < x) return std::make_pair(first, second);
  return std::make_pair(second, first);
}

bool hole_crosses(const FluidRegion& region, double x, double clearance) {
  for (std::size_t h = 1; h < region.loops.size(); ++h)
    for (const BoundaryCurve& c : region.loops[h]) {
      const auto [lo, hi] = x_extent(c);
      if (lo <= x + clearance && hi >= x - clearance) return true;
    }
  return false;
}

}  // namespace

std::optional<RegionPieces> split_region(const FluidRegion& region, const std::function<double(Vec2)>& size,
                                         int pieces) {
  if (region.loops.empty() || pieces < 2) return std::nullopt;
  const CellColumns columns(region, size);
  if (!columns.usable()) return std::nullopt;
  const double clearance = kEndClearance * region.domain.width();
  RegionPieces r;
  std::vector<Loop> outer;  // the outer loops of the pieces so far; the last is still to be cut
  Loop rest;
  for (const BoundaryCurve& c : region.loops.front()) rest.push_back({c, -1});
  for (int k = 1; k < pieces; ++k) {
    const double f = static_cast<double>(k) / pieces;
    for (const double shift : kCutShifts) {
      const double x = columns.x_at(std::clamp(f + shift, 0.0, 1.0));
      if ((!r.x.empty() && x <= r.x.back() + clearance) || hole_crosses(region, x, clearance)) continue;
      auto parts = cut_loop(rest, x, static_cast<int>(r.x.size()), clearance);
      if (!parts) continue;
      r.x.push_back(x);
      outer.push_back(std::move(parts->first));
      rest = std::move(parts->second);
      break;
    }
  }
  if (r.x.empty()) return std::nullopt;
  outer.push_back(std::move(rest));
  for (Loop& o : outer) r.loops.push_back({std::move(o)});
  // Each hole goes to the piece between the cuts round it.
  for (std::size_t h = 1; h < region.loops.size(); ++h) {
    const double x = x_extent(region.loops[h].front()).first;
    const auto piece = static_cast<std::size_t>(std::upper_bound(r.x.begin(), r.x.end(), x) - r.x.begin());
    Loop hole;
    for (const BoundaryCurve& c : region.loops[h]) hole.push_back({c, -1});
    r.loops[piece].push_back(std::move(hole));
  }
  return r;
}

}  // namespace meshgen
