#include "pipeline/equal_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;
constexpr double kInf = std::numeric_limits<double>::infinity();
// A 95% interval spans +-1.96 standard deviations of a normal variable.
constexpr double kZ95 = 1.959963984540054;
// A run's own error interval enters as a log-normal scatter; past this
// relative width the error is unknown anyway and the cap keeps one bad run
// from dominating every draw.
constexpr double kMaxLogErrorSd = 1.0;
// Fraction of Monte Carlo draws allowed to be undefined (a family whose
// drawn slope does not fall with cost on both sides) before the interval is
// reported as unbounded.
constexpr double kMaxUndefinedFraction = 0.05;

struct Sample {
  double log_cost, log_error;
};

// Least squares in the (log cost, log error) plane, parametrised by the
// mean log error at the mean log cost (uncorrelated with the slope).
struct Centred {
  bool ok = false;
  int n = 0;
  double mean_x = 0, sxx = 0, c = 0, b = 0, s = 0;
};

Centred fit_centred(const std::vector<Sample>& pts) {
  Centred f;
  f.n = static_cast<int>(pts.size());
  if (f.n < 3) return f;
  double mx = 0, my = 0;
  for (const auto& p : pts) {
    mx += p.log_cost;
    my += p.log_error;
  }
  mx /= f.n;
  my /= f.n;
  double sxx = 0, sxy = 0;
  for (const auto& p : pts) {
    sxx += (p.log_cost - mx) * (p.log_cost - mx);
    sxy += (p.log_cost - mx) * (p.log_error - my);
  }
  if (!(sxx > 0)) return f;
  f.mean_x = mx;
  f.sxx = sxx;
  f.b = sxy / sxx;
  f.c = my;
  double ss = 0;
  for (const auto& p : pts) {
    const double r = p.log_error - (f.c + f.b * (p.log_cost - mx));
    ss += r * r;
  }
  f.s = std::sqrt(ss / (f.n - 2));
  f.ok = std::isfinite(f.b) && std::isfinite(f.s);
  return f;
}

std::vector<Sample> samples_of(const std::vector<CostError>& runs) {
  std::vector<Sample> pts;
  for (const auto& r : runs)
    if (std::isfinite(r.cost) && r.cost > 0 && std::isfinite(r.error) && r.error > 0)
      pts.push_back({std::log(r.cost), std::log(r.error)});
  return pts;
}

std::vector<double> log_error_sd(const std::vector<CostError>& runs) {
  std::vector<double> sd;
  for (const auto& r : runs)
    if (std::isfinite(r.cost) && r.cost > 0 && std::isfinite(r.error) && r.error > 0)
      sd.push_back(std::isfinite(r.error_ci) && r.error_ci > 0
                       ? std::min(kMaxLogErrorSd, r.error_ci / (kZ95 * r.error))
                       : 0.0);
  return sd;
}

// log cost at log error `le` on a fit with centre c and slope b; +inf when
// the slope does not fall (refining that family never reaches the error).
double log_cost_on(double mean_x, double c, double b, double le) {
  if (!(b < 0)) return kInf;
  return mean_x + (le - c) / b;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto k = static_cast<std::size_t>(pos);
  if (k + 1 >= v.size()) return v.back();
  const double f = pos - static_cast<double>(k);
  if (std::isinf(v[k]) || std::isinf(v[k + 1])) return f < 0.5 ? v[k] : v[k + 1];
  return v[k] + f * (v[k + 1] - v[k]);
}

// One draw of a family's log cost at `le`: the runs' errors perturbed by
// their own intervals, refitted, then the coefficients drawn from their
// sampling distribution (a t with n - 2 degrees of freedom).
class FamilyDraw {
 public:
  explicit FamilyDraw(const std::vector<CostError>& runs) : pts_(samples_of(runs)), sd_(log_error_sd(runs)) {}
  bool usable() const { return fit_centred(pts_).ok; }
  double nominal(double le) const {
    const Centred f = fit_centred(pts_);
    return log_cost_on(f.mean_x, f.c, f.b, le);
  }
  double draw(double le, std::mt19937_64& rng) const {
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Sample> p = pts_;
    for (std::size_t i = 0; i < p.size(); ++i) p[i].log_error += sd_[i] * normal(rng);
    const Centred f = fit_centred(p);
    if (!f.ok) return kNaN;
    const int dof = f.n - 2;
    std::chi_squared_distribution<double> chi2(dof);
    const double w = std::sqrt(dof / std::max(chi2(rng), 1e-300));
    const double c = f.c + w * f.s / std::sqrt(static_cast<double>(f.n)) * normal(rng);
    const double b = f.b + w * f.s / std::sqrt(f.sxx) * normal(rng);
    return log_cost_on(f.mean_x, c, b, le);
  }

 private:
  std::vector<Sample> pts_;
  std::vector<double> sd_;
};

// log(exp(log_cost) + fixed): a family's log cost with its fixed part.
double with_fixed(double log_cost, double fixed) {
  if (!(fixed > 0) || !std::isfinite(log_cost)) return log_cost;
  return std::log(std::exp(log_cost) + fixed);
}

}  // namespace

double LogLogFit::log_cost_at(double error) const {
  if (!ok || !(b < 0) || !(error > 0)) return kNaN;
  return (std::log(error) - a) / b;
}

LogLogFit fit_log_log(const std::vector<CostError>& runs) {
  const Centred f = fit_centred(samples_of(runs));
  LogLogFit r;
  r.n = f.n;
  if (!f.ok) return r;
  r.ok = true;
  r.b = f.b;
  r.a = f.c - f.b * f.mean_x;
  r.residual_sd = f.s;
  r.mean_log_cost = f.mean_x;
  r.sxx = f.sxx;
  return r;
}

Interval cost_ratio_at_error(const std::vector<CostError>& slow, const std::vector<CostError>& fast,
                             double target_error, const EqualErrorOptions& o) {
  return cost_ratio_at_error(FamilyPair{slow, fast}, target_error, o);
}

Interval cost_ratio_at_error(const FamilyPair& runs, double target_error,
                             const EqualErrorOptions& o) {
  return cost_ratio_at_error(
      runs, [&](std::mt19937_64&) { return runs; }, target_error, o);
}

Interval cost_ratio_at_error(const FamilyPair& nominal, const CostSampler& sample, double target_error,
                             const EqualErrorOptions& o) {
  Interval out{kNaN, kNaN, kNaN};
  const FamilyDraw s(nominal.slow), f(nominal.fast);
  if (!(target_error > 0) || !std::isfinite(target_error) || !s.usable() || !f.usable()) return out;
  const double le = std::log(target_error);
  out.value = std::exp(with_fixed(s.nominal(le), nominal.slow_fixed) -
                       with_fixed(f.nominal(le), nominal.fast_fixed));
  std::mt19937_64 rng(o.seed);
  std::vector<double> ratios;
  ratios.reserve(static_cast<std::size_t>(o.draws));
  int undefined = 0;
  for (int k = 0; k < o.draws; ++k) {
    const FamilyPair drawn = sample(rng);
    const FamilyDraw ds(drawn.slow), df(drawn.fast);
    const double d = with_fixed(ds.draw(le, rng), drawn.slow_fixed) -
                     with_fixed(df.draw(le, rng), drawn.fast_fixed);
    if (std::isnan(d)) ++undefined;
    else ratios.push_back(d);
  }
  if (ratios.empty() || undefined > kMaxUndefinedFraction * o.draws) {
    out.ci_low = 0.0;
    out.ci_high = kInf;
    return out;
  }
  constexpr double kTail = 0.025;
  out.ci_low = std::exp(percentile(ratios, kTail));
  out.ci_high = std::exp(percentile(ratios, 1.0 - kTail));
  return out;
}

std::string verdict_of(const Interval& speedup) {
  if (!(speedup.ci_low > 0) && !(speedup.ci_high > 0)) return "not distinguishable";
  if (speedup.ci_low > 1.0) return "faster";
  if (speedup.ci_high < 1.0) return "slower";
  return "not distinguishable";
}

double cheapest_cost_at(std::vector<CostError> runs, double error) {
  std::erase_if(runs, [](const CostError& r) { return !(r.cost > 0) || !std::isfinite(r.error); });
  std::sort(runs.begin(), runs.end(), [](const CostError& a, const CostError& b) { return a.cost < b.cost; });
  constexpr double kErrorFloor = 1e-12;  // log-log interpolation needs errors > 0
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (runs[k].error <= error) return runs[k].cost;
    if (k + 1 < runs.size() && runs[k + 1].error <= error) {
      const double e0 = std::max(runs[k].error, kErrorFloor), e1 = std::max(runs[k + 1].error, kErrorFloor);
      const double t = (std::log(std::max(error, kErrorFloor)) - std::log(e0)) / (std::log(e1) - std::log(e0));
      return std::exp(std::log(runs[k].cost) + t * (std::log(runs[k + 1].cost) - std::log(runs[k].cost)));
    }
  }
  return kNaN;
}

}  // namespace pipeline
