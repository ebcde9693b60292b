#include "shockfit/shock_line.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "scene/units.hpp"

namespace shockfit {

namespace {
constexpr double kMadToSigma = 1.4826;
}

LineFit fit_orthogonal_line(const std::vector<scene::Vec2>& pts) {
  LineFit l;
  if (pts.size() < 2) return {{scene::kNaN, scene::kNaN}, {scene::kNaN, scene::kNaN}, scene::kNaN};
  scene::Vec2 c{};
  for (const auto p : pts) c += p;
  c = c / static_cast<double>(pts.size());
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  for (const auto p : pts) {
    const Eigen::Vector2d d(p.x - c.x, p.y - c.y);
    m += d * d.transpose();
  }
  // The principal axis of the scatter minimises the perpendicular distances.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m);
  const Eigen::Vector2d v = es.eigenvectors().col(1);  // largest eigenvalue
  scene::Vec2 dir{v(0), v(1)};
  if (dir.x < 0 || (dir.x == 0 && dir.y < 0)) dir = -dir;
  l.point = c;
  l.dir = dir;
  l.angle_deg = std::atan2(dir.y, dir.x) / scene::kDeg;
  return l;
}

std::vector<std::size_t> within_robust_sigmas(const std::vector<double>& residuals, double sigmas,
                                              double floor) {
  std::vector<std::size_t> keep;
  if (residuals.empty()) return keep;
  std::vector<double> a(residuals.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::abs(residuals[i]);
  const std::vector<double> d = a;
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  const double limit = std::max(sigmas * kMadToSigma * a[a.size() / 2], floor);
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] <= limit) keep.push_back(i);
  return keep;
}

std::vector<std::size_t> near_median(const std::vector<double>& values, double sigmas,
                                     double floor) {
  if (values.empty()) return {};
  std::vector<double> v = values;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
  const double mid =
      v.size() % 2 == 1
          ? v[h]
          : 0.5 * (v[h] + *std::max_element(v.begin(), v.begin() + static_cast<long>(h)));
  std::vector<double> centred;
  centred.reserve(values.size());
  for (const double x : values) centred.push_back(x - mid);
  return within_robust_sigmas(centred, sigmas, floor);
}

std::vector<std::size_t> inliers(const std::vector<scene::Vec2>& pts, double sigmas, double floor) {
  if (pts.size() < 3) {
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < pts.size(); ++i) keep.push_back(i);
    return keep;
  }
  const LineFit l = fit_orthogonal_line(pts);
  const scene::Vec2 nrm = scene::perp(l.dir);
  std::vector<double> d(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) d[i] = scene::dot(pts[i] - l.point, nrm);
  return within_robust_sigmas(d, sigmas, floor);
}

std::pair<double, double> fit_axis_parabola(const std::vector<scene::Vec2>& pts) {
  const auto n = static_cast<Eigen::Index>(pts.size());
  if (n < 2) return {scene::kNaN, scene::kNaN};
  Eigen::MatrixXd X(n, 2);
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    X(k, 0) = 1.0;
    X(k, 1) = pts[static_cast<std::size_t>(k)].y * pts[static_cast<std::size_t>(k)].y;
    y(k) = pts[static_cast<std::size_t>(k)].x;
  }
  const Eigen::Vector2d c = X.colPivHouseholderQr().solve(y);
  return {c(0), c(1)};
}

}  // namespace shockfit
