#include "pipeline/bow_shock_check.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace pipeline {

namespace {
// Width of the band tested against the fit, in cells: the axis cell row and
// the two beside it, where a carbuncle's bump sits.
constexpr double kAxisBandCells = 3.0;
constexpr int kMinFitPoints = 4;

struct ShockPoint {
  scene::Vec2 at;
  double cell_area;
};

using EdgeKey = std::pair<std::pair<double, double>, std::pair<double, double>>;
EdgeKey edge_key(scene::Vec2 a, scene::Vec2 b) {
  std::pair<double, double> p{a.x, a.y}, q{b.x, b.y};
  if (q < p) std::swap(p, q);
  return {p, q};
}

// Points where rho crosses rho_mid across an interior edge (the two cells'
// polygons share the edge's vertices exactly: both come from one point list).
std::vector<ShockPoint> shock_points(const cfd::Mesh2D& mesh, const std::vector<double>& rho,
                                     double rho_mid) {
  std::map<EdgeKey, std::size_t> first_cell;
  std::vector<ShockPoint> out;
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    const auto& poly = mesh.cell_polygons[c];
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const auto [it, fresh] =
          first_cell.emplace(edge_key(poly[i], poly[(i + 1) % poly.size()]), c);
      if (fresh) continue;
      const std::size_t o = it->second;
      const double ra = rho[o] - rho_mid, rb = rho[c] - rho_mid;
      if ((ra < 0) == (rb < 0)) continue;
      const double t = ra / (ra - rb);
      out.push_back({mesh.cell_centre[o] + t * (mesh.cell_centre[c] - mesh.cell_centre[o]),
                     0.5 * (std::abs(mesh.cell_area[o]) + std::abs(mesh.cell_area[c]))});
    }
  }
  return out;
}
}  // namespace

AxisShockCheck check_axis_shock(const cfd::Mesh2D& mesh, const std::vector<double>& rho,
                                double rho_mid, double x_max, double y_max) {
  AxisShockCheck r;
  std::vector<ShockPoint> pts = shock_points(mesh, rho, rho_mid);
  std::erase_if(pts,
                [&](const ShockPoint& p) { return p.at.x >= x_max || std::abs(p.at.y) > y_max; });
  if (pts.empty()) return r;
  // Cell size at the shock near the axis: the closest third of the points in |y|.
  std::sort(pts.begin(), pts.end(), [](const ShockPoint& a, const ShockPoint& b) {
    return std::abs(a.at.y) < std::abs(b.at.y);
  });
  const std::size_t near = std::max<std::size_t>(1, pts.size() / 3);
  double area = 0;
  for (std::size_t i = 0; i < near; ++i) area += pts[i].cell_area;
  r.cell_size = std::sqrt(area / static_cast<double>(near));
  const double band = kAxisBandCells * r.cell_size;

  // Least squares x = a + b y^2 over the points off the axis band.
  double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
  for (const auto& p : pts) {
    if (std::abs(p.at.y) < band) {
      ++r.axis_points;
      continue;
    }
    const double q = p.at.y * p.at.y;
    s0 += 1;
    s1 += q;
    s2 += q * q;
    t0 += p.at.x;
    t1 += q * p.at.x;
    ++r.fit_points;
  }
  const double det = s0 * s2 - s1 * s1;
  if (r.fit_points < kMinFitPoints || r.axis_points == 0 || !(det > 0)) return r;
  const double a = (t0 * s2 - s1 * t1) / det, b = (s0 * t1 - s1 * t0) / det;
  double worst = 0;
  for (const auto& p : pts)
    if (std::abs(p.at.y) < band)
      worst = std::max(worst, std::abs(p.at.x - (a + b * p.at.y * p.at.y)));
  r.deviation_cells = worst / r.cell_size;
  return r;
}

}  // namespace pipeline
