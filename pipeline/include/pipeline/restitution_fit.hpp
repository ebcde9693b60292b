#pragma once
// Smooth models of the calibrated restitution e(M, theta): weighted least
// squares over the calibration's training wedges, and the choice between
// models by their leave-one-out error.
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pipeline {

// Candidates, simplest first. The constant is a baseline: a model must beat
// it out of sample to claim that e depends on Mach number at all. Two
// Mach-only shapes: 1/M^2 levels off at high Mach number (the hypersonic
// limit of the shock angle), ln M keeps falling (the training crossings
// still fall between Mach 4.5 and 6); the leave-one-out error chooses.
// With the deflection: linear in theta, or 1/theta, which levels off at
// large deflections as the crossings do (M2.5-6: e drops by 0.004-0.008
// from 8 to 14 deg and by at most 0.001 from 14 to 20). Last, ln M bent by
// (ln M)^2 with 1/theta: a grid of seven Mach numbers resolves the crossings'
// curvature in Mach number that three or four cannot (34 training wedges:
// leave-one-out angle error 0.35 deg against 0.48 for ln M + 1/theta).
// Beyond 20 deg the crossings turn up again as the shock nears detachment
// (M3: e 0.9825 at 20 deg, 0.9830 at 23, 0.9856 at 26), which 1/theta alone
// cannot follow: the last form adds theta^2, giving e a minimum in the
// deflection.
enum class RestitutionModel {
  constant,
  inverse_mach2,
  log_mach,
  inverse_mach2_angle,
  log_mach_angle,
  log_mach_inverse_angle,
  log_mach2_inverse_angle,
  log_mach2_inverse_angle_angle2
};
inline constexpr RestitutionModel kRestitutionModels[] = {
    RestitutionModel::constant,
    RestitutionModel::inverse_mach2,
    RestitutionModel::log_mach,
    RestitutionModel::inverse_mach2_angle,
    RestitutionModel::log_mach_angle,
    RestitutionModel::log_mach_inverse_angle,
    RestitutionModel::log_mach2_inverse_angle,
    RestitutionModel::log_mach2_inverse_angle_angle2};

std::string model_key(RestitutionModel m);      // "inverse_mach2", as in the table
std::string model_formula(RestitutionModel m);  // "e = c0 + c1/M^2", for people
std::optional<RestitutionModel> model_from_key(const std::string& key);
std::size_t parameter_count(RestitutionModel m);
bool uses_angle(RestitutionModel m);

// One calibrated wedge: the crossing e and its 95% half-width.
struct RestitutionPoint {
  double mach = 0, angle_deg = 0;
  double restitution = 1, restitution_ci = 0;
};

// A point's weight in the fits: 1 / max(ci, floor)^2.
double fit_weight(const RestitutionPoint& p);

struct RestitutionFit {
  RestitutionModel model = RestitutionModel::inverse_mach2;
  std::vector<double> coefficients;  // c0, c1, ... as in model_formula
  double residual_sd = 0;            // unweighted sd of e about the fit, n - p degrees of freedom
  double loo_rms = 0;  // weighted RMS of the leave-one-out e residuals (NaN: not computed)
  // The model's e; the angle is ignored by models that do not use it.
  double evaluate(double mach, double angle_deg) const;
};

// Weighted least squares with weights 1 / max(ci, floor)^2. nullopt when
// there are fewer points than coefficients or the design is singular
// (e.g. every point at one Mach number). loo_rms is left NaN.
std::optional<RestitutionFit> fit_restitution(std::span<const RestitutionPoint> points,
                                              RestitutionModel model);

// e of point i predicted by the model fitted to every other point.
std::optional<double> leave_one_out_restitution(std::span<const RestitutionPoint> points,
                                                RestitutionModel model, std::size_t i);

// sqrt(sum w_i r_i^2 / sum w_i) over the leave-one-out residuals
// r_i = e_i - e_fit(-i)(M_i, theta_i), with the fit's weights. nullopt when
// some left-out fit is impossible.
std::optional<double> leave_one_out_rms(std::span<const RestitutionPoint> points,
                                        RestitutionModel model);

struct ModelChoice {
  std::vector<RestitutionFit> candidates;  // every model that could be fitted, with loo_rms
  std::size_t chosen = 0;                  // index into candidates
  const RestitutionFit& fit() const { return candidates.at(chosen); }
};
// Fits every model and picks the smallest leave-one-out error; a richer
// model must lower it by more than a rounding-level margin, so exact data
// (every model at zero) keeps the simplest. nullopt when no model fits.
std::optional<ModelChoice> choose_restitution_model(std::span<const RestitutionPoint> points);

}  // namespace pipeline
