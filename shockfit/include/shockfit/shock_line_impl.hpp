#pragma once
// Template part of shock_line.hpp.
#include <algorithm>
#include <cmath>
#include <random>

#include "scene/units.hpp"

namespace shockfit {

template <class Stat>
Interval bootstrap(const std::vector<scene::Vec2>& pts, const std::vector<scene::Vec2>& normals,
                   const std::vector<double>& sigmas, int resamples, std::uint64_t seed, Stat stat) {
  std::mt19937_64 rng(seed);
  const std::size_t n = pts.size();
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(resamples));
  std::vector<scene::Vec2> sample(n);
  for (int r = 0; r < resamples; ++r) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = pick(rng);
      sample[k] = pts[i] + (sigmas[i] * gauss(rng)) * normals[i];
    }
    const double v = stat(sample);
    if (std::isfinite(v)) values.push_back(v);
  }
  if (values.empty()) return {scene::kNaN, scene::kNaN};
  std::sort(values.begin(), values.end());
  auto q = [&](double p) {
    const double x = p * static_cast<double>(values.size() - 1);
    const auto i = static_cast<std::size_t>(x);
    const double f = x - static_cast<double>(i);
    return i + 1 < values.size() ? (1 - f) * values[i] + f * values[i + 1] : values[i];
  };
  return {q(0.025), q(0.975)};
}

}  // namespace shockfit
