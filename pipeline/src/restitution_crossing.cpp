#include "pipeline/restitution_crossing.hpp"

#include <algorithm>
#include <cmath>

#include "pipeline/calibration.hpp"

namespace pipeline {

namespace {
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
