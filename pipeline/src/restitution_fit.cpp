#include "pipeline/restitution_fit.hpp"

#include <cmath>

#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;

// A crossing's 95% half-width below this counts as this much: one lucky
// sweep (two nearly equal intervals) must not outweigh every other wedge.
constexpr double kMinRestitutionCi = 1e-4;
// A design column whose part orthogonal to the previous ones is below this
// fraction of its norm makes the fit singular (e.g. every point at one Mach).
constexpr double kRankTolerance = 1e-10;
// A richer model must lower the leave-one-out error by more than this to be
// chosen: on exact data every adequate model scores ~1e-16, and the
// simplest one should win that tie.
constexpr double kLooTieTolerance = 1e-12;

std::vector<double> basis(RestitutionModel m, double mach, double angle_deg) {
  switch (m) {
    case RestitutionModel::constant:
      return {1.0};
    case RestitutionModel::inverse_mach2:
      return {1.0, 1.0 / (mach * mach)};
    case RestitutionModel::log_mach:
      return {1.0, std::log(mach)};
    case RestitutionModel::inverse_mach2_angle:
      return {1.0, 1.0 / (mach * mach), angle_deg};
    case RestitutionModel::log_mach_angle:
      return {1.0, std::log(mach), angle_deg};
    case RestitutionModel::log_mach_inverse_angle:
      return {1.0, std::log(mach), 1.0 / angle_deg};
    case RestitutionModel::log_mach2_inverse_angle:
      return {1.0, std::log(mach), std::log(mach) * std::log(mach), 1.0 / angle_deg};
    case RestitutionModel::log_mach2_inverse_angle_angle2:
      return {1.0, std::log(mach), std::log(mach) * std::log(mach), 1.0 / angle_deg,
              angle_deg * angle_deg};
  }
  return {};
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// Weighted least squares by modified Gram-Schmidt QR of sqrt(W) A (the
// normal equations would square the condition number of the 1/M^2 and
// theta columns). Point `skip` (if < size) is left out.
std::optional<std::vector<double>> solve(std::span<const RestitutionPoint> pts, RestitutionModel m,
                                         std::size_t skip) {
  const std::size_t p = parameter_count(m);
  std::vector<std::vector<double>> cols(p);
  std::vector<double> rhs;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i == skip) continue;
    const double sw = std::sqrt(fit_weight(pts[i]));
    const auto row = basis(m, pts[i].mach, pts[i].angle_deg);
    for (std::size_t j = 0; j < p; ++j) cols[j].push_back(sw * row[j]);
    rhs.push_back(sw * pts[i].restitution);
  }
  if (rhs.size() < p) return std::nullopt;
  std::vector<std::vector<double>> r(p, std::vector<double>(p, 0.0));
  std::vector<double> z(p, 0.0);
  for (std::size_t j = 0; j < p; ++j) {
    auto& v = cols[j];
    const double norm0 = std::sqrt(dot(v, v));
    for (std::size_t k = 0; k < j; ++k) {
      r[k][j] = dot(cols[k], v);
      for (std::size_t i = 0; i < v.size(); ++i) v[i] -= r[k][j] * cols[k][i];
    }
    const double norm = std::sqrt(dot(v, v));
    if (!(norm > kRankTolerance * norm0)) return std::nullopt;
    r[j][j] = norm;
    for (auto& x : v) x /= norm;
    z[j] = dot(v, rhs);
    for (std::size_t i = 0; i < rhs.size(); ++i) rhs[i] -= z[j] * v[i];
  }
  std::vector<double> c(p, 0.0);
  for (std::size_t j = p; j-- > 0;) {
    double s = z[j];
    for (std::size_t k = j + 1; k < p; ++k) s -= r[j][k] * c[k];
    c[j] = s / r[j][j];
  }
  return c;
}

double evaluate_coefficients(RestitutionModel m, const std::vector<double>& c, double mach,
                             double angle_deg) {
  const auto row = basis(m, mach, angle_deg);
  double e = 0;
  for (std::size_t j = 0; j < row.size() && j < c.size(); ++j) e += c[j] * row[j];
  return e;
}
}  // namespace

double fit_weight(const RestitutionPoint& p) {
  // An interval that is not a positive number carries no information on the
  // weight; it is taken at the floor like a very small one.
  const double ci = std::isfinite(p.restitution_ci) ? std::max(p.restitution_ci, kMinRestitutionCi)
                                                    : kMinRestitutionCi;
  return 1.0 / (ci * ci);
}

std::string model_key(RestitutionModel m) {
  switch (m) {
    case RestitutionModel::constant:
      return "constant";
    case RestitutionModel::inverse_mach2:
      return "inverse_mach2";
    case RestitutionModel::log_mach:
      return "log_mach";
    case RestitutionModel::inverse_mach2_angle:
      return "inverse_mach2_angle";
    case RestitutionModel::log_mach_angle:
      return "log_mach_angle";
    case RestitutionModel::log_mach_inverse_angle:
      return "log_mach_inverse_angle";
    case RestitutionModel::log_mach2_inverse_angle:
      return "log_mach2_inverse_angle";
    case RestitutionModel::log_mach2_inverse_angle_angle2:
      return "log_mach2_inverse_angle_angle2";
  }
  return "";
}

std::string model_formula(RestitutionModel m) {
  switch (m) {
    case RestitutionModel::constant:
      return "e = c0";
    case RestitutionModel::inverse_mach2:
      return "e = c0 + c1/M^2";
    case RestitutionModel::log_mach:
      return "e = c0 + c1*ln(M)";
    case RestitutionModel::inverse_mach2_angle:
      return "e = c0 + c1/M^2 + c2*theta_deg";
    case RestitutionModel::log_mach_angle:
      return "e = c0 + c1*ln(M) + c2*theta_deg";
    case RestitutionModel::log_mach_inverse_angle:
      return "e = c0 + c1*ln(M) + c2/theta_deg";
    case RestitutionModel::log_mach2_inverse_angle:
      return "e = c0 + c1*ln(M) + c2*ln(M)^2 + c3/theta_deg";
    case RestitutionModel::log_mach2_inverse_angle_angle2:
      return "e = c0 + c1*ln(M) + c2*ln(M)^2 + c3/theta_deg + c4*theta_deg^2";
  }
  return "";
}

std::optional<RestitutionModel> model_from_key(const std::string& key) {
  for (const auto m : kRestitutionModels)
    if (model_key(m) == key) return m;
  return std::nullopt;
}

std::size_t parameter_count(RestitutionModel m) {
  // One coefficient per basis function; any finite point gives the length.
  return basis(m, 2.0, 10.0).size();
}

bool uses_angle(RestitutionModel m) {
  // Read off the basis, so a new form cannot be left out: its functions at
  // two deflections differ exactly when it uses the angle.
  return basis(m, 2.0, 10.0) != basis(m, 2.0, 20.0);
}

double RestitutionFit::evaluate(double mach, double angle_deg) const {
  return evaluate_coefficients(model, coefficients, mach, angle_deg);
}

std::optional<RestitutionFit> fit_restitution(std::span<const RestitutionPoint> points,
                                              RestitutionModel model) {
  const auto c = solve(points, model, points.size());
  if (!c) return std::nullopt;
  RestitutionFit f;
  f.model = model;
  f.coefficients = *c;
  f.loo_rms = kNaN;
  const std::size_t p = parameter_count(model);
  if (points.size() > p) {
    double ss = 0;
    for (const auto& pt : points) {
      const double r = pt.restitution - f.evaluate(pt.mach, pt.angle_deg);
      ss += r * r;
    }
    f.residual_sd = std::sqrt(ss / static_cast<double>(points.size() - p));
  } else {
    f.residual_sd = kNaN;  // an exact interpolation has no scatter to estimate
  }
  return f;
}

std::optional<double> leave_one_out_restitution(std::span<const RestitutionPoint> points,
                                                RestitutionModel model, std::size_t i) {
  if (i >= points.size()) return std::nullopt;
  const auto c = solve(points, model, i);
  if (!c) return std::nullopt;
  return evaluate_coefficients(model, *c, points[i].mach, points[i].angle_deg);
}

std::optional<double> leave_one_out_rms(std::span<const RestitutionPoint> points,
                                        RestitutionModel model) {
  if (points.empty()) return std::nullopt;
  double swr = 0, sw = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto e = leave_one_out_restitution(points, model, i);
    if (!e) return std::nullopt;
    const double r = points[i].restitution - *e;
    swr += fit_weight(points[i]) * r * r;
    sw += fit_weight(points[i]);
  }
  return std::sqrt(swr / sw);
}

std::optional<ModelChoice> choose_restitution_model(std::span<const RestitutionPoint> points) {
  ModelChoice out;
  for (const auto m : kRestitutionModels) {
    auto f = fit_restitution(points, m);
    const auto loo = leave_one_out_rms(points, m);
    if (!f || !loo) continue;
    f->loo_rms = *loo;
    // Candidates come simplest first: a later one replaces the choice only
    // when it is clearly better out of sample.
    if (out.candidates.empty() ||
        f->loo_rms < out.candidates[out.chosen].loo_rms - kLooTieTolerance)
      out.chosen = out.candidates.size();
    out.candidates.push_back(*f);
  }
  if (out.candidates.empty()) return std::nullopt;
  return out;
}

}  // namespace pipeline
