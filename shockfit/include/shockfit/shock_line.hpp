#pragma once
// Fits through shock points: a straight line (attached shocks) and a
// parabola about the axis (detached shocks), with bootstrap intervals.
#include <cstdint>
#include <vector>

#include "scene/vec2.hpp"

namespace shockfit {

struct LineFit {
  scene::Vec2 point, dir;  // centroid and unit direction (dir.x >= 0)
  double angle_deg = 0.0;  // from +x
};

// Orthogonal (total least squares) line through the points.
LineFit fit_orthogonal_line(const std::vector<scene::Vec2>& pts);

// Indices of residuals within `sigmas` robust sigmas (MAD of the residuals
// about zero, as Gaussian sigma) of zero, and at least `floor`.
std::vector<std::size_t> within_robust_sigmas(const std::vector<double>& residuals, double sigmas,
                                              double floor);

// Indices of values within `sigmas` robust sigmas (and at least `floor`) of
// their median (the mean of the middle two for an even count).
std::vector<std::size_t> near_median(const std::vector<double>& values, double sigmas,
                                     double floor);

// Indices of points within `sigmas` robust sigmas (and at least `floor`) of
// the line fitted through all of them.
std::vector<std::size_t> inliers(const std::vector<scene::Vec2>& pts, double sigmas, double floor);

struct Interval {
  double lo = 0.0, hi = 0.0;
};

// Bootstrap over points: resample with replacement and move each resampled
// point along its normal by N(0, sigma_i); 2.5 and 97.5 percentiles of `stat`.
template <class Stat>
Interval bootstrap(const std::vector<scene::Vec2>& pts, const std::vector<scene::Vec2>& normals,
                   const std::vector<double>& sigmas, int resamples, std::uint64_t seed, Stat stat);

// x = x0 + c y^2 by least squares; returns {x0, c}.
std::pair<double, double> fit_axis_parabola(const std::vector<scene::Vec2>& pts);

}  // namespace shockfit

#include "shockfit/shock_line_impl.hpp"
