#pragma once
// Synthetic shock curves for meshgen tests: the exact oblique shock of a
// wedge (theta-beta-Mach), Billig's hyperbola ahead of a blunt body, written
// as shock.csv the way shockfit writes it (columns by name).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace meshgen_test {

inline std::string case_path(const std::string& name) {
  return std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml";
}

inline std::string fresh_dir(const std::string& name) {
  return test_support::fresh_dir("meshgen_test_" + name);
}

// The predicted shock of a case scene: exact for wedges, Billig's
// correlation (nose radius = half-height, as scene_domain estimates it) for
// blunt bodies. `points` along the curve, from the symmetry line outwards.
inline std::vector<scene::Vec2> predicted_shock(const scene::Scene& s, int points = 40) {
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  std::vector<scene::Vec2> out;
  const double m = s.freestream.mach;
  if (const auto attached = scene::attached_shock_beta(s)) {
    const double beta = *attached;
    const double xend = d.xmax * 1.2;  // runs past the outlet on purpose
    for (int i = 0; i < points; ++i) {
      const double x = xend * i / (points - 1);
      out.push_back({x, x * std::tan(beta)});
    }
    return out;
  }
  double h = 0.0, xfront = g.polyline.front().x;
  for (const scene::Vec2 p : g.polyline) { h = std::max(h, p.y); xfront = std::min(xfront, p.x); }
  const double vertex = xfront - scene::billig_standoff_cylinder(m) * h;
  const double ymax = d.ymax * 1.1;  // leaves the domain through the top or outlet
  for (int i = 0; i < points; ++i) {
    const double y = ymax * i / (points - 1);
    out.push_back({vertex + scene::billig_shock_x(m, h, y), y});
  }
  return out;
}

inline void write_shock_csv(const std::string& path, const std::vector<scene::Vec2>& pts, double ci,
                            bool with_ci = true) {
  std::ofstream f(path);
  f << "station,shock_x,shock_y" << (with_ci ? ",ci" : "") << ",accepted\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    f << i << "," << pts[i].x << "," << pts[i].y;
    if (with_ci) f << "," << ci;
    f << ",1\n";
  }
}

}  // namespace meshgen_test
