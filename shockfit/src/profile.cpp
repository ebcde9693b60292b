#include "shockfit/profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shockfit {

namespace {
// Samples per lattice spacing along the normal: two resolve the breakpoint
// to half a cell; more would only add correlated samples.
constexpr double kSamplesPerCell = 2.0;
// A bilinear sample mixes the cells within one spacing either side, so the
// noise of samples decorrelates over about two lattice spacings.
constexpr double kCorrelationCells = 2.0;
// inside_body is 0/1 per cell; any bilinear weight of a body cell makes the
// sample a mix of body and flow, so it is skipped.
constexpr double kInsideBodyTolerance = 1e-12;

// Parameter where the ray origin + t n leaves [lo, hi] along one axis.
double exit_param(double o, double n, double lo, double hi) {
  if (n > 0) return (hi - o) / n;
  if (n < 0) return (lo - o) / n;
  return std::numeric_limits<double>::infinity();
}
}  // namespace

double spacing_along(const scene::Lattice& lat, scene::Vec2 n) {
  return 1.0 / std::hypot(n.x / lat.dx, n.y / lat.dy);
}

Profile sample_profile(const scene::Lattice& lat, const std::string& field, const scene::Domain& d,
                       scene::Vec2 origin, scene::Vec2 normal, int min_samples) {
  Profile p;
  p.spacing = spacing_along(lat, normal);
  p.step = p.spacing / kSamplesPerCell;
  const double xlo = std::max(d.xmin, lat.x0), xhi = std::min(d.xmax, lat.x0 + lat.nx * lat.dx);
  const double ylo = std::max(d.ymin, lat.y0), yhi = std::min(d.ymax, lat.y0 + lat.ny * lat.dy);
  const double tmax = std::min(exit_param(origin.x, normal.x, xlo, xhi), exit_param(origin.y, normal.y, ylo, yhi));
  if (!(tmax > 0.0) || !std::isfinite(tmax)) return p;
  const bool has_inside = lat.has("inside_body");
  const bool has_samples = lat.has("samples") && min_samples > 0;
  const int n = static_cast<int>(std::floor(tmax / p.step));
  for (int k = 0; k <= n; ++k) {
    const double t = k * p.step;
    const scene::Vec2 q = origin + t * normal;
    double v = 0.0, aux = 0.0;
    if (!lat.sample(field, q.x, q.y, v)) continue;
    if (has_inside && (!lat.sample("inside_body", q.x, q.y, aux) || aux > kInsideBodyTolerance)) continue;
    if (has_samples && (!lat.sample("samples", q.x, q.y, aux) || aux < min_samples)) continue;
    p.t.push_back(t);
    p.f.push_back(v);
  }
  return p;
}

TwoLineOptions two_line_options(const Profile& p, const scene::ShockfitParams& params) {
  TwoLineOptions opt;
  opt.window = params.window * p.spacing;
  opt.correlation = kCorrelationCells * p.spacing / std::max(p.step, 1e-300);
  opt.noise_factor = params.noise_factor;
  // Each line spans at least the shock window, so a line never fits the
  // jump alone.
  opt.min_segment = std::max(opt.min_segment, static_cast<int>(std::ceil(opt.window / std::max(p.step, 1e-300))));
  return opt;
}

}  // namespace shockfit
