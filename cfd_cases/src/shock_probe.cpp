#include "shock_probe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "case_setup.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace cfd {

namespace {
// The stagnation line is probed this far (a fraction of the body length)
// above the symmetry line: a symmetric case's line is its boundary, and the
// cells that matter are the ones just inside; nor should a cell edge lying
// on the line count twice.
constexpr double kLineOffset = 1e-6;
constexpr double kRightAngle = 0.5 * M_PI;
}  // namespace

std::optional<ShockProbe> ShockProbe::for_scene(const scene::Scene& s,
                                                const std::vector<Mesh2D>& parts) {
  if (!scene::shock_may_stand_off(s)) return std::nullopt;
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const double y0 = g.nose.y + kLineOffset * g.length;
  std::vector<Sample> samples;
  std::size_t offset = 0;
  for (const Mesh2D& m : parts) {
    for (std::size_t c = 0; c < m.cells(); ++c) {
      const auto& poly = m.cell_polygons[c];
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const scene::Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        if ((a.y - y0) * (b.y - y0) >= 0) continue;
        const double x = a.x + (y0 - a.y) / (b.y - a.y) * (b.x - a.x);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      const double mid = 0.5 * (lo + hi);
      if (hi > lo && mid < g.nose.x) samples.push_back({mid, offset + c});
    }
    offset += m.cells();
  }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.x < b.x; });
  const Freestream f = freestream(s);
  const double rho_ratio = scene::oblique_density_ratio(f.mach, kRightAngle, f.gamma);
  return ShockProbe(std::move(samples), 0.5 * f.rho() * (1.0 + rho_ratio));
}

ShockReading ShockProbe::measure(const std::vector<double>& rho) const {
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    const double r = rho[samples_[k].cell];
    if (r < rho_mid_) continue;
    if (k == 0)
      return {samples_[0].x, samples_.size() > 1 ? samples_[1].x - samples_[0].x : scene::kNaN};
    const Sample& a = samples_[k - 1];
    const double ra = rho[a.cell];
    const double dx = samples_[k].x - a.x;
    return {a.x + (rho_mid_ - ra) / (r - ra) * dx, dx};
  }
  return {scene::kNaN, scene::kNaN};
}

}  // namespace cfd
