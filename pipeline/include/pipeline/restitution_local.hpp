#pragma once
// The smooth e(M, theta) model's lack of fit, taken out where the training
// wedges show it. The crossings turn up towards detachment at a deflection
// that depends on the Mach number (earlier at low Mach), which no separable
// smooth form follows; a kernel average of the model's residuals does,
// without a new global term. It is a candidate like the smooth models: the
// calibration keeps it only when it lowers the leave-one-out error.
#include <optional>
#include <span>
#include <vector>

#include "pipeline/restitution_fit.hpp"
#include "scene/units.hpp"

namespace pipeline {

// correction(M, theta) = sum k_i w_i r_i / (sum k_i w_i + k_fade w_mean):
// a locally constant (Nadaraya-Watson) average of the residuals
// r_i = e_i - model(M_i, theta_i) with Gaussian kernels k_i in ln M and theta
// and the fit's weights w_i. The k_fade term lets the correction fade to the
// smooth model beyond the training wedges (about two bandwidths out), where
// the residuals say nothing.
struct LocalCorrection {
  double bandwidth_log_mach = 0;            // kernel width in ln M
  double bandwidth_angle_deg = 0;           // kernel width in theta (deg)
  double loo_rms = scene::kNaN;             // the corrected model's, weighted as the fit's
  std::vector<RestitutionPoint> residuals;  // restitution holds r_i, restitution_ci as the point's
  double evaluate(double mach, double angle_deg) const;
};

// The correction of `fit` at these bandwidths, from its residuals at `points`.
LocalCorrection local_correction(std::span<const RestitutionPoint> points,
                                 const RestitutionFit& fit, double bandwidth_log_mach,
                                 double bandwidth_angle_deg);

// e of point i from the model and its correction, both made without point i.
std::optional<double> leave_one_out_corrected(std::span<const RestitutionPoint> points,
                                              RestitutionModel model, double bandwidth_log_mach,
                                              double bandwidth_angle_deg, std::size_t i);

// A correction's kernel widths.
struct CorrectionWidths {
  double log_mach = 0;   // in ln M
  double angle_deg = 0;  // in theta (deg)
};

// The bandwidths (from a fixed grid, or `held` alone) whose corrected model
// has the smallest leave-one-out error, kept only when that error is clearly
// below the model's own (`fit.loo_rms`); nullopt otherwise, or for a model
// that ignores the angle.
std::optional<LocalCorrection> choose_local_correction(
    std::span<const RestitutionPoint> points, const RestitutionFit& fit,
    const std::optional<CorrectionWidths>& held = std::nullopt);

}  // namespace pipeline
