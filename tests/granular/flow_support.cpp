#include "flow_support.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "scratch.hpp"

namespace flowtest {

double upstream_mean(const scene::Lattice& lat, const std::string& field, double x_max) {
  const auto& f = lat.field(field);
  const auto& inside = lat.field("inside_body");
  double s = 0;
  int k = 0;
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) {
      const std::size_t c = lat.index(i, j);
      if (lat.xc(i) < x_max && inside[c] == 0.0 && std::isfinite(f[c])) {
        s += f[c];
        ++k;
      }
    }
  return k ? s / k : std::nan("");
}

double max_of(const scene::Lattice& lat, const std::string& field) {
  double m = -1e300;
  for (const double v : lat.field(field))
    if (std::isfinite(v)) m = std::max(m, v);
  return m;
}

std::optional<ShockFit> fit_wedge_shock(const scene::Lattice& lat, double threshold, double x_lo, double x_hi) {
  const auto& nu = lat.field("volume_fraction");
  std::vector<double> xs, ys;
  for (int i = 0; i < lat.nx; ++i) {
    const double x = lat.xc(i);
    if (x < x_lo || x > x_hi) continue;
    for (int j = lat.ny - 1; j > 0; --j) {
      const double a = nu[lat.index(i, j)], b = nu[lat.index(i, j - 1)];
      if (std::isfinite(a) && std::isfinite(b) && a < threshold && b >= threshold) {
        // Linear interpolation of the crossing between the two cell centres.
        const double t = (threshold - a) / (b - a);
        xs.push_back(x);
        ys.push_back(lat.yc(j) - t * lat.dy);
        break;
      }
    }
  }
  const auto n = static_cast<double>(xs.size());
  if (xs.size() < 3) return std::nullopt;
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    mx += xs[k] / n;
    my += ys[k] / n;
  }
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    sxx += (xs[k] - mx) * (xs[k] - mx);
    sxy += (xs[k] - mx) * (ys[k] - my);
  }
  const double slope = sxy / sxx, icpt = my - slope * mx;
  double rss = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) rss += std::pow(ys[k] - icpt - slope * xs[k], 2);
  const double se_slope = std::sqrt(rss / (n - 2) / sxx);
  ShockFit fit;
  fit.angle_deg = std::atan(slope) * 180.0 / std::numbers::pi;
  fit.angle_se_deg = se_slope / (1 + slope * slope) * 180.0 / std::numbers::pi;
  fit.points = static_cast<int>(xs.size());
  return fit;
}

std::string temp_dir(const std::string& name) {
  return test_support::fresh_dir("granular_flow_test_" + name);
}

}  // namespace flowtest
