#include "pipeline/restitution_local.hpp"

#include <cmath>

namespace pipeline {

namespace {
using scene::kNaN;

// The bandwidths tried. In ln M the training grid's Mach steps are 0.11-0.18
// apart, so 0.05 keeps a wedge's own Mach number and 0.2 spans about two
// steps; in theta the steps are 1.5-3 deg.
constexpr double kBandwidthsLogMach[] = {0.05, 0.1, 0.2};
constexpr double kBandwidthsAngleDeg[] = {2.0, 4.0, 8.0};
// A kernel this small (two bandwidths out in one coordinate, exp(-2^2/2))
// weighs as much as the mean training point in the denominator, so the
// correction fades to the smooth model where no training wedge is near.
const double kFadeKernel = std::exp(-2.0);
// The chosen bandwidths are the best of nine by the same leave-one-out
// error that judges them, which flatters them: they must lower the smooth
// model's error by more than this fraction to be kept.
constexpr double kRequiredGain = 0.10;

double kernel(const RestitutionPoint& p, double mach, double angle_deg, double h_log_mach,
              double h_angle_deg) {
  const double u = (std::log(p.mach) - std::log(mach)) / h_log_mach;
  const double v = (p.angle_deg - angle_deg) / h_angle_deg;
  return std::exp(-0.5 * (u * u + v * v));
}

std::vector<RestitutionPoint> without(std::span<const RestitutionPoint> points, std::size_t i) {
  std::vector<RestitutionPoint> out;
  for (std::size_t j = 0; j < points.size(); ++j)
    if (j != i) out.push_back(points[j]);
  return out;
}
}  // namespace

double LocalCorrection::evaluate(double mach, double angle_deg) const {
  if (residuals.empty()) return 0;
  double num = 0, den = 0, w_sum = 0;
  for (const auto& r : residuals) {
    const double w = fit_weight(r);
    const double kw = kernel(r, mach, angle_deg, bandwidth_log_mach, bandwidth_angle_deg) * w;
    num += kw * r.restitution;
    den += kw;
    w_sum += w;
  }
  const double w_mean = w_sum / static_cast<double>(residuals.size());
  return num / (den + kFadeKernel * w_mean);
}

LocalCorrection local_correction(std::span<const RestitutionPoint> points,
                                 const RestitutionFit& fit, double bandwidth_log_mach,
                                 double bandwidth_angle_deg) {
  LocalCorrection c;
  c.bandwidth_log_mach = bandwidth_log_mach;
  c.bandwidth_angle_deg = bandwidth_angle_deg;
  for (const auto& p : points) {
    RestitutionPoint r = p;
    r.restitution = p.restitution - fit.evaluate(p.mach, p.angle_deg);
    c.residuals.push_back(r);
  }
  return c;
}

namespace {
// Point i's e from `fit` (the model refitted without it) and the correction
// built on the other points.
double corrected_left_out(std::span<const RestitutionPoint> rest, const RestitutionPoint& p,
                          const RestitutionFit& fit, double bandwidth_log_mach,
                          double bandwidth_angle_deg) {
  const auto c = local_correction(rest, fit, bandwidth_log_mach, bandwidth_angle_deg);
  return fit.evaluate(p.mach, p.angle_deg) + c.evaluate(p.mach, p.angle_deg);
}
}  // namespace

std::optional<double> leave_one_out_corrected(std::span<const RestitutionPoint> points,
                                              RestitutionModel model, double bandwidth_log_mach,
                                              double bandwidth_angle_deg, std::size_t i) {
  if (i >= points.size()) return std::nullopt;
  const auto rest = without(points, i);
  const auto fit = fit_restitution(rest, model);
  if (!fit) return std::nullopt;
  return corrected_left_out(rest, points[i], *fit, bandwidth_log_mach, bandwidth_angle_deg);
}

std::optional<LocalCorrection> choose_local_correction(
    std::span<const RestitutionPoint> points, const RestitutionFit& fit,
    const std::optional<CorrectionWidths>& held) {
  if (!uses_angle(fit.model) || !std::isfinite(fit.loo_rms) || points.size() < 2)
    return std::nullopt;
  // The model refitted without each point, once: every width's left-out
  // correction stands on the same fits.
  std::vector<std::vector<RestitutionPoint>> rests;
  std::vector<RestitutionFit> left_out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    rests.push_back(without(points, i));
    const auto f = fit_restitution(rests.back(), fit.model);
    if (!f) return std::nullopt;
    left_out.push_back(*f);
  }
  std::vector<CorrectionWidths> grid;
  if (held)
    grid.push_back(*held);
  else
    for (const double hm : kBandwidthsLogMach)
      for (const double ht : kBandwidthsAngleDeg) grid.push_back({hm, ht});
  std::optional<LocalCorrection> best;
  for (const auto& [hm, ht] : grid) {
    double swr = 0, sw = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double r =
          points[i].restitution - corrected_left_out(rests[i], points[i], left_out[i], hm, ht);
      swr += fit_weight(points[i]) * r * r;
      sw += fit_weight(points[i]);
    }
    const double loo = std::sqrt(swr / sw);
    if (!best || loo < best->loo_rms) {
      best = local_correction(points, fit, hm, ht);
      best->loo_rms = loo;
    }
  }
  if (best && best->loo_rms < (1.0 - kRequiredGain) * fit.loo_rms) return best;
  return std::nullopt;
}

}  // namespace pipeline
