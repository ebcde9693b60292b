#include "pipeline/restitution_crossing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "pipeline/calibration.hpp"
#include "shockfit/group_interval.hpp"

namespace pipeline {

namespace {
// A fit with a wider 95% interval than this is noise, not a shock angle.
constexpr double kMaxUsableCiDeg = 5.0;
// A bracket this many times steeper than the segment above it is a step
// (with its rise beyond the runs' intervals). At 3: none of the 88
// crossings at Mach 2-8 swept at 4 flow-through times (1 of 18 at Mach
// 9-10), 3 of 18 at Mach 7-8 and 7 of 18 at Mach 9-10 swept at 12; ratios 2
// and 5 change that by one crossing at most (docs/calibration.md).
constexpr double kStepSlopeRatio = 3.0;
bool already_run(const std::vector<SweepPoint>& pts, double e) {
  return std::any_of(pts.begin(), pts.end(), [e](const SweepPoint& p) {
    return std::abs(p.e - e) < 0.5 * kSweepRestitutionStep;
  });
}

std::optional<double> fresh(const std::vector<SweepPoint>& pts, double e) {
  const double r = swept_restitution(e);
  if (!(r > 0) || already_run(pts, r)) return std::nullopt;  // swept_restitution clamps at e = 1
  return r;
}
}  // namespace

double swept_restitution(double e) {
  return std::min(kMaxRestitution, std::round(e / kSweepRestitutionStep) * kSweepRestitutionStep);
}

bool usable(const SweepPoint& p) {
  return std::isfinite(p.angle) && p.angle > 0.0 && p.angle < 90.0 && std::isfinite(p.ci) &&
         p.ci < kMaxUsableCiDeg;
}

std::optional<Crossing> find_crossing(const std::vector<SweepPoint>& pts, double target) {
  std::vector<SweepPoint> ok;
  for (const auto& p : pts)
    if (usable(p)) ok.push_back(p);
  for (std::size_t k = ok.size(); k-- > 1;) {
    const SweepPoint a = ok[k - 1], b = ok[k];
    if ((a.angle - target) * (b.angle - target) <= 0 && a.angle != b.angle) {
      const double slope = (b.angle - a.angle) / (b.e - a.e);
      return Crossing{a.e + (target - a.angle) / slope, std::abs(0.5 * (a.ci + b.ci) / slope), a.e,
                      b.e};
    }
  }
  return std::nullopt;
}

bool crossing_on_step(const std::vector<SweepPoint>& pts, double target) {
  const auto c = find_crossing(pts, target);
  if (!c) return false;
  std::optional<SweepPoint> lo, hi, above;
  for (const auto& p : pts) {
    if (!usable(p)) continue;
    if (p.e == c->e_low) lo = p;
    if (p.e == c->e_high) hi = p;
    if (p.e > c->e_high && (!above || p.e < above->e)) above = p;
  }
  if (!lo || !hi || !above) return false;
  const double rise = hi->angle - lo->angle;
  const double slope = rise / (hi->e - lo->e);
  const double slope_above = std::max(0.0, (above->angle - hi->angle) / (above->e - hi->e));
  const double rise_expected = slope_above * (hi->e - lo->e);
  return slope > kStepSlopeRatio * slope_above && rise - rise_expected > std::hypot(lo->ci, hi->ci);
}

std::optional<Crossing> find_crossing_by_line(const std::vector<SweepPoint>& pts, double target,
                                              double window) {
  const auto c = find_crossing(pts, target);
  if (!c) return std::nullopt;
  // Weighted sums about the bracket's crossing, in units of the runs' sd.
  double s = 0, sx = 0, sxx = 0, sy = 0, sxy = 0;
  std::vector<SweepPoint> near;
  for (const auto& p : pts)
    if (usable(p) && p.ci > 0 && std::abs(p.e - c->e) <= window) {
      const double sd = p.ci / shockfit::kNormal95;
      const double w = 1.0 / (sd * sd), x = p.e - c->e;
      s += w;
      sx += w * x;
      sxx += w * x * x;
      sy += w * p.angle;
      sxy += w * x * p.angle;
      near.push_back(p);
    }
  if (near.size() < 3) return c;
  const double det = s * sxx - sx * sx;
  if (!(det > 0)) return c;
  const double slope = (s * sxy - sx * sy) / det;
  const double at = (sxx * sy - sx * sxy) / det;
  double rise = 0;  // the bracketing pair's: the line must run the same way
  for (const auto& p : pts)
    if (usable(p) && (p.e == c->e_low || p.e == c->e_high))
      rise += p.e == c->e_high ? p.angle : -p.angle;
  if (!(slope * rise > 0)) return c;
  double chi2 = 0;
  for (const auto& p : near) {
    const double sd = p.ci / shockfit::kNormal95, r = p.angle - at - slope * (p.e - c->e);
    chi2 += r * r / (sd * sd);
  }
  const double dof = static_cast<double>(near.size()) - 2.0;
  const double scale = std::max(1.0, chi2 / dof);
  const double x = (target - at) / slope;
  if (std::abs(x) > window) return c;
  const double var = (sxx - 2.0 * x * sx + x * x * s) / det / (slope * slope) * scale;
  return Crossing{c->e + x, shockfit::kNormal95 * std::sqrt(var), c->e_low, c->e_high};
}

std::optional<Crossing> find_crossing_by_curve(const std::vector<SweepPoint>& pts, double target,
                                               double window) {
  const auto c = find_crossing(pts, target);
  if (!c) return std::nullopt;
  std::vector<SweepPoint> near;
  for (const auto& p : pts)
    if (usable(p) && p.ci > 0 && std::abs(p.e - c->e) <= window) near.push_back(p);
  const auto by_line = [&] { return find_crossing_by_line(pts, target, window); };
  if (near.size() < 3) return by_line();
  // Weighted normal equations of angle = a + b x + q x^2, x = e - c.e, in
  // units of the runs' sd.
  Eigen::Matrix3d n = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (const auto& p : near) {
    const double sd = p.ci / shockfit::kNormal95, x = p.e - c->e;
    const Eigen::Vector3d f(1.0, x, x * x);
    n += f * f.transpose() / (sd * sd);
    r += f * p.angle / (sd * sd);
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(n);
  if (!lu.isInvertible()) return by_line();
  const Eigen::Matrix3d cov = lu.inverse();
  const Eigen::Vector3d k = cov * r;
  const double a = k(0) - target, b = k(1), q = k(2);
  // The root nearest the bracket's crossing: (-b + sqrt(b^2 - 4aq)) / 2q
  // for b > 0, written so that q -> 0 leaves the line's root -a/b.
  const double disc = b * b - 4.0 * a * q;
  if (!(disc >= 0) || b == 0) return by_line();
  const double x = -2.0 * a / (b + std::copysign(std::sqrt(disc), b));
  const double slope = b + 2.0 * q * x;
  double rise = 0;  // the bracketing pair's: the curve must run the same way
  for (const auto& p : pts)
    if (usable(p) && (p.e == c->e_low || p.e == c->e_high))
      rise += p.e == c->e_high ? p.angle : -p.angle;
  if (!(slope * rise > 0) || std::abs(x) > window) return by_line();
  // Monotone across the bracket, where the root lies: the parabola's vertex
  // outside it (runs that bend the curve over there are noise, not shape).
  if (q != 0) {
    const double vertex = c->e - b / (2.0 * q);
    if (vertex >= c->e_low && vertex <= c->e_high) return by_line();
  }
  double chi2 = 0;
  for (const auto& p : near) {
    const double sd = p.ci / shockfit::kNormal95, dx = p.e - c->e;
    const double res = p.angle - k(0) - b * dx - q * dx * dx;
    chi2 += res * res / (sd * sd);
  }
  const double dof = static_cast<double>(near.size()) - 3.0;
  const double scale = dof > 0 ? std::max(1.0, chi2 / dof) : 1.0;
  // The root moves with the coefficients as -(1, x, x^2) / slope.
  const Eigen::Vector3d g = Eigen::Vector3d(1.0, x, x * x) / slope;
  const double var = g.dot(cov * g) * scale;
  return Crossing{c->e + x, shockfit::kNormal95 * std::sqrt(var), c->e_low, c->e_high};
}

SweepPoint mean_point(double e, const std::vector<SweepPoint>& runs) {
  double sw = 0, swx = 0;
  for (const auto& p : runs)
    if (usable(p) && p.ci > 0) {
      const double w = 1.0 / (p.ci * p.ci);
      sw += w;
      swx += w * p.angle;
    }
  if (!(sw > 0)) return {e, std::nan(""), std::nan("")};
  return {e, swx / sw, 1.0 / std::sqrt(sw)};
}

std::uint64_t nth_seed(std::uint64_t base, int k) {
  return base + static_cast<std::uint64_t>(k) * kSeedStride;
}

std::string seed_dir(const std::string& dir, int k, std::uint64_t seed) {
  return k == 0 ? dir : dir + "_seed" + std::to_string(seed);
}

std::optional<double> next_restitution(const std::vector<SweepPoint>& pts, double target) {
  if (const auto c = find_crossing(pts, target)) return fresh(pts, 0.5 * (c->e_low + c->e_high));
  std::vector<SweepPoint> ok;
  for (const auto& p : pts)
    if (usable(p)) ok.push_back(p);
  if (ok.empty()) return std::nullopt;
  const bool all_above =
      std::all_of(ok.begin(), ok.end(), [&](const SweepPoint& p) { return p.angle > target; });
  const bool all_below =
      std::all_of(ok.begin(), ok.end(), [&](const SweepPoint& p) { return p.angle < target; });
  // Less dissipation (larger e) stands the shock at a larger angle: search
  // below the usable runs when they are all above the gas angle, above when below.
  if (all_above) {
    const double lo = ok.front().e;
    double beyond = -1;
    for (const auto& p : pts)
      if (p.e < lo) beyond = std::max(beyond, p.e);
    if (beyond > 0) return fresh(pts, 0.5 * (lo + beyond));
    if (ok.size() < 2) return std::nullopt;
    return fresh(pts, 2 * lo - ok[1].e);
  }
  if (all_below) {
    const double hi = ok.back().e;
    double beyond = 2 * kMaxRestitution;
    for (const auto& p : pts)
      if (p.e > hi) beyond = std::min(beyond, p.e);
    if (beyond <= kMaxRestitution) return fresh(pts, 0.5 * (hi + beyond));
    if (ok.size() < 2) return std::nullopt;
    return fresh(pts, std::min(kMaxRestitution, 2 * hi - ok[ok.size() - 2].e));
  }
  return std::nullopt;  // angles on both sides but no neighbouring pair crosses: cannot happen
}

}  // namespace pipeline
