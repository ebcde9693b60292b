#pragma once
// Synthetic lattice fields with a known shock, for the shockfit tests.
#include <cmath>
#include <functional>
#include <random>

#include "scene/body.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"

namespace shockfit_test {

// Lattice of spacing h over the scene's domain, with inside_body and
// samples fields (NaN inside the body, like the granular output).
inline scene::Lattice domain_lattice(const scene::Scene& s, double h) {
  const scene::Domain d = scene::scene_domain(s);
  const int nx = static_cast<int>(std::ceil(d.width() / h)), ny = static_cast<int>(std::ceil(d.height() / h));
  scene::Lattice lat(nx, ny, d.xmin, d.ymin, h, h);
  const scene::BodyGeometry g = scene::make_body(*s.body);
  auto& inside = lat.add("inside_body", 0.0);
  auto& samples = lat.add("samples", 1000.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (scene::point_in_body(g, {lat.xc(i), lat.yc(j)})) {
        inside[lat.index(i, j)] = 1.0;
        samples[lat.index(i, j)] = 0.0;
      }
  return lat;
}

// fields[name] = value(x, y) + N(0, sigma) outside the body, NaN inside.
inline void fill(scene::Lattice& lat, const std::string& name, const std::function<double(double, double)>& value,
                 double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto& f = lat.add(name);
  const auto& inside = lat.field("inside_body");
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) {
      const std::size_t k = lat.index(i, j);
      const double e = sigma * noise(rng);
      f[k] = inside[k] > 0 ? std::nan("") : value(lat.xc(i), lat.yc(j)) + e;
    }
}

// Cell average of value(x, y) by n x n sub-samples (the exact inviscid
// solution rendered on the lattice).
inline void fill_cell_average(scene::Lattice& lat, const std::string& name,
                              const std::function<double(double, double)>& value, int n) {
  auto& f = lat.add(name);
  const auto& inside = lat.field("inside_body");
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) {
      const std::size_t k = lat.index(i, j);
      if (inside[k] > 0) {
        f[k] = std::nan("");
        continue;
      }
      double sum = 0.0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          sum += value(lat.x0 + (i + (a + 0.5) / n) * lat.dx, lat.y0 + (j + (b + 0.5) / n) * lat.dy);
      f[k] = sum / (n * n);
    }
}

}  // namespace shockfit_test
