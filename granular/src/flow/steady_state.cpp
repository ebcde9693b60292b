#include "steady_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace granular {

namespace {
double mean_of(const std::vector<double>& x, std::size_t from, std::size_t to) {
  double s = 0;
  for (std::size_t k = from; k < to; ++k) s += x[k];
  return s / static_cast<double>(to - from);
}

std::string format(const char* fmt, double a, double b, double c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}
}  // namespace

bool counts_settled(const std::vector<double>& counts, std::size_t window, double rel_tol,
                    double noise_sigmas) {
  if (window == 0 || counts.size() < 2 * window) return false;
  const std::size_t n = counts.size();
  const double a = mean_of(counts, n - 2 * window, n - window);
  const double b = mean_of(counts, n - window, n);
  // Counting noise: a window's mean of a Poisson-like count b has standard
  // error sqrt(b / window).
  const double noise = noise_sigmas * std::sqrt(std::max(b, 1.0) / static_cast<double>(window));
  return std::abs(b - a) <= std::max(rel_tol * b, noise);
}

bool FlowSteadyState::add(double time, double count) {
  counts_.push_back(count);
  if (steady_) return false;
  if (c_.check_every == 0 || counts_.size() % c_.check_every != 0) return false;
  if (time < c_.min_time) {
    why_ = format("too early: time %.4g of %.4g (%.0f samples)", time, c_.min_time,
                  static_cast<double>(counts_.size()));
    return false;
  }
  if (counts_.size() < 2 * c_.window) {
    why_ = format("too few samples: %.0f of %.0f (time %.4g)", static_cast<double>(counts_.size()),
                  static_cast<double>(2 * c_.window), time);
    return true;
  }
  steady_ = counts_settled(counts_, c_.window, c_.rel_tol, c_.noise_sigmas);
  const std::size_t n = counts_.size();
  const double a = mean_of(counts_, n - 2 * c_.window, n - c_.window);
  const double b = mean_of(counts_, n - c_.window, n);
  why_ = format(steady_ ? "steady: window means %.6g -> %.6g at time %.4g"
                        : "drifting: window means %.6g -> %.6g at time %.4g",
                a, b, time);
  return true;
}

}  // namespace granular
