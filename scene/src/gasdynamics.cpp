#include "scene/gasdynamics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scene {

namespace {
// tan(theta) as a function of beta (theta-beta-Mach relation).
double tan_theta(double m, double beta, double g) {
  const double s = std::sin(beta);
  return 2.0 / std::tan(beta) * (m * m * s * s - 1.0) / (m * m * (g + std::cos(2 * beta)) + 2.0);
}
// Golden-section maximum of theta(beta) on [mu, pi/2].
double beta_at_max(double m, double g) {
  double a = std::asin(1.0 / m), b = std::numbers::pi / 2;
  const double r = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 200; ++k) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (tan_theta(m, c, g) > tan_theta(m, d, g)) b = d; else a = c;
  }
  return 0.5 * (a + b);
}
}  // namespace

double max_deflection(double mach, double gamma) {
  if (mach <= 1.0) return 0.0;
  return std::atan(tan_theta(mach, beta_at_max(mach, gamma), gamma));
}

std::optional<double> oblique_shock_beta(double mach, double theta, double gamma) {
  if (mach <= 1.0 || theta < 0.0) return std::nullopt;
  const double bmax = beta_at_max(mach, gamma);
  const double target = std::tan(theta);
  if (tan_theta(mach, bmax, gamma) < target) return std::nullopt;
  // theta(beta) rises monotonically from 0 at the Mach angle to its maximum:
  // bisection on the weak branch converges to round-off.
  double a = std::asin(1.0 / mach), b = bmax;
  for (int k = 0; k < 200; ++k) {
    const double c = 0.5 * (a + b);
    if (tan_theta(mach, c, gamma) < target) a = c; else b = c;
  }
  return 0.5 * (a + b);
}

double oblique_pressure_ratio(double mach, double beta, double gamma) {
  const double mn = mach * std::sin(beta);
  return 1.0 + 2.0 * gamma / (gamma + 1.0) * (mn * mn - 1.0);
}

double oblique_density_ratio(double mach, double beta, double gamma) {
  const double mn2 = std::pow(mach * std::sin(beta), 2);
  return (gamma + 1.0) * mn2 / ((gamma - 1.0) * mn2 + 2.0);
}

double oblique_downstream_mach(double mach, double beta, double theta, double gamma) {
  const double mn2 = std::pow(mach * std::sin(beta), 2);
  const double mn2d = (1.0 + 0.5 * (gamma - 1.0) * mn2) / (gamma * mn2 - 0.5 * (gamma - 1.0));
  return std::sqrt(mn2d) / std::sin(beta - theta);
}

double oblique_deflection(double mach, double beta, double gamma) {
  return std::atan(std::max(0.0, tan_theta(mach, beta, gamma)));
}

double rest_start_min_mach(double gamma) {
  return 2.0 / std::sqrt(3.0 - gamma);
}

double rayleigh_pitot_ratio(double mach, double gamma) {
  const double m2 = mach * mach, g = gamma;
  if (mach <= 1.0) return std::pow(1.0 + 0.5 * (g - 1.0) * m2, g / (g - 1.0));
  const double stagnation = std::pow((g + 1.0) * (g + 1.0) * m2 / (4.0 * g * m2 - 2.0 * (g - 1.0)), g / (g - 1.0));
  return stagnation * (1.0 - g + 2.0 * g * m2) / (g + 1.0);
}

double billig_standoff_cylinder(double mach) { return 0.386 * std::exp(4.67 / (mach * mach)); }
double billig_standoff_sphere(double mach) { return 0.143 * std::exp(3.24 / (mach * mach)); }
double billig_shock_radius_cylinder(double mach) {
  return 1.386 * std::exp(1.8 / std::pow(mach - 1.0, 0.75));
}

double billig_shock_x(double mach, double radius, double y) {
  const double rc = billig_shock_radius_cylinder(mach) * radius;
  const double t = std::tan(std::asin(1.0 / mach));
  return rc / (t * t) * (std::sqrt(1.0 + y * y * t * t / (rc * rc)) - 1.0);
}

double billig_shock_y(double mach, double radius, double x) {
  const double rc = billig_shock_radius_cylinder(mach) * radius;
  const double t = std::tan(std::asin(1.0 / mach));
  const double q = 1.0 + x * t * t / rc;
  return rc / t * std::sqrt(q * q - 1.0);
}

}  // namespace scene
