#include "pipeline/restitution_crossing.hpp"

#include <algorithm>
#include <cmath>

#include "pipeline/calibration.hpp"

namespace pipeline {

namespace {
// The two-sided 95% quantile of the normal distribution: a run's interval
// over its standard deviation.
constexpr double kZ95 = 1.96;
// A fit with a wider 95% interval than this is noise, not a shock angle.
constexpr double kMaxUsableCiDeg = 5.0;
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

std::optional<Crossing> find_crossing_by_line(const std::vector<SweepPoint>& pts, double target,
                                              double window) {
  const auto c = find_crossing(pts, target);
  if (!c) return std::nullopt;
  // Weighted sums about the bracket's crossing, in units of the runs' sd.
  double s = 0, sx = 0, sxx = 0, sy = 0, sxy = 0;
  std::vector<SweepPoint> near;
  for (const auto& p : pts)
    if (usable(p) && p.ci > 0 && std::abs(p.e - c->e) <= window) {
      const double sd = p.ci / kZ95;
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
    const double sd = p.ci / kZ95, r = p.angle - at - slope * (p.e - c->e);
    chi2 += r * r / (sd * sd);
  }
  const double dof = static_cast<double>(near.size()) - 2.0;
  const double scale = std::max(1.0, chi2 / dof);
  const double x = (target - at) / slope;
  if (std::abs(x) > window) return c;
  const double var = (sxx - 2.0 * x * sx + x * x * s) / det / (slope * slope) * scale;
  return Crossing{c->e + x, kZ95 * std::sqrt(var), c->e_low, c->e_high};
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
