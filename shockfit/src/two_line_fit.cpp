#include "shockfit/two_line_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace shockfit {

namespace {

// MAD -> Gaussian sigma.
constexpr double kMadToSigma = 1.4826;
// A profile with no noise at all (exact synthetic data) still needs a
// positive noise scale for the tests below; relative to the profile's size.
constexpr double kNoiseFloorRel = 1e-9;
// A jump must explain the profile much better than one smooth curve: the two
// lines' squared error must be below this fraction of a single quadratic's.
// Smooth subsonic profiles (and pure noise) give ratios near 1; a shock, a
// ratio near (noise / jump)^2.
constexpr double kSmoothRejectRatio = 0.5;
constexpr int kBisectIterations = 100;

struct Sums {
  std::vector<double> n, t, f, tt, tf, ff;
};

double segment_sse(const Sums& s, int i, int j) {
  const double n = s.n[j] - s.n[i];
  const double st = s.t[j] - s.t[i], sf = s.f[j] - s.f[i];
  const double stt = s.tt[j] - s.tt[i], stf = s.tf[j] - s.tf[i], sff = s.ff[j] - s.ff[i];
  const double vtt = stt - st * st / n, vtf = stf - st * sf / n, vff = sff - sf * sf / n;
  return std::max(0.0, vtt > 0.0 ? vff - vtf * vtf / vtt : vff);
}

// Least-squares line over samples [i, j) with Eigen (QR); variances are
// filled in later from the pooled noise.
Line fit_line(const std::vector<double>& t, const std::vector<double>& f, int i, int j,
              Eigen::Matrix2d& xtx_inv) {
  const int n = j - i;
  Eigen::MatrixXd X(n, 2);
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) {
    X(k, 0) = 1.0;
    X(k, 1) = t[i + k];
    y(k) = f[i + k];
  }
  const Eigen::Vector2d c = X.colPivHouseholderQr().solve(y);
  xtx_inv = (X.transpose() * X).inverse();
  Line l;
  l.a = c(0);
  l.b = c(1);
  return l;
}

double quadratic_sse(const std::vector<double>& t, const std::vector<double>& f) {
  const int n = static_cast<int>(t.size());
  const double t0 = 0.5 * (t.front() + t.back()), scale = std::max(0.5 * (t.back() - t.front()), 1e-300);
  Eigen::MatrixXd X(n, 3);
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) {
    const double u = (t[k] - t0) / scale;
    X(k, 0) = 1.0;
    X(k, 1) = u;
    X(k, 2) = u * u;
    y(k) = f[k];
  }
  const Eigen::VectorXd c = X.colPivHouseholderQr().solve(y);
  return (X * c - y).squaredNorm();
}

double line_integral(const Line& l, double a, double b) {
  return l.a * (b - a) + 0.5 * l.b * (b * b - a * a);
}

}  // namespace

int best_breakpoint(const std::vector<double>& t, const std::vector<double>& f, int min_segment) {
  const int n = static_cast<int>(t.size());
  const int m = std::max(min_segment, 2);
  if (n < 2 * m) return -1;
  // Centre and scale so the running sums do not cancel catastrophically.
  double tm = 0.0, fm = 0.0;
  for (int k = 0; k < n; ++k) { tm += t[k]; fm += f[k]; }
  tm /= n;
  fm /= n;
  Sums s;
  for (auto* v : {&s.n, &s.t, &s.f, &s.tt, &s.tf, &s.ff}) v->assign(static_cast<std::size_t>(n) + 1, 0.0);
  for (int k = 0; k < n; ++k) {
    const double u = t[k] - tm, g = f[k] - fm;
    s.n[k + 1] = s.n[k] + 1.0;
    s.t[k + 1] = s.t[k] + u;
    s.f[k + 1] = s.f[k] + g;
    s.tt[k + 1] = s.tt[k] + u * u;
    s.tf[k + 1] = s.tf[k] + u * g;
    s.ff[k + 1] = s.ff[k] + g * g;
  }
  int best = -1;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int k = m; k <= n - m; ++k) {
    const double sse = segment_sse(s, 0, k) + segment_sse(s, k, n);
    if (sse < best_sse) {
      best_sse = sse;
      best = k;
    }
  }
  return best;
}

TwoLineFit fit_two_lines(const std::vector<double>& t, const std::vector<double>& f,
                         const TwoLineOptions& opt) {
  TwoLineFit r;
  const int n = static_cast<int>(t.size());
  const int k = best_breakpoint(t, f, opt.min_segment);
  if (k < 0) return r;
  r.valid = true;
  r.breakpoint = k;
  r.t_break = 0.5 * (t[k - 1] + t[k]);
  Eigen::Matrix2d inv_in, inv_out;
  r.inner = fit_line(t, f, 0, k, inv_in);
  r.outer = fit_line(t, f, k, n, inv_out);

  std::vector<double> res(static_cast<std::size_t>(n));
  double sse = 0.0, fmax = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = f[i] - (i < k ? r.inner.at(t[i]) : r.outer.at(t[i]));
    res[i] = std::abs(e);
    sse += e * e;
    fmax = std::max(fmax, std::abs(f[i]));
  }
  r.rms = std::sqrt(sse / n);
  std::nth_element(res.begin(), res.begin() + n / 2, res.end());
  r.noise = std::max(kMadToSigma * res[n / 2], kNoiseFloorRel * std::max(fmax, 1e-300));

  // Neighbouring samples share lattice cells, so they are not independent:
  // inflate the variances by the number of samples per independent one.
  const double var_scale = r.noise * r.noise * std::max(opt.correlation, 1.0);
  for (auto [line, inv] : {std::pair{&r.inner, &inv_in}, std::pair{&r.outer, &inv_out}}) {
    line->var_a = var_scale * (*inv)(0, 0);
    line->var_b = var_scale * (*inv)(1, 1);
    line->cov_ab = var_scale * (*inv)(0, 1);
  }

  r.step = r.outer.at(r.t_break) - r.inner.at(r.t_break);
  const double se_step = std::sqrt(r.inner.var_at(r.t_break) + r.outer.var_at(r.t_break));
  const double db = r.inner.b - r.outer.b;
  const double se_db = std::sqrt(r.inner.var_b + r.outer.var_b);
  const double lo = std::max(t.front(), r.t_break - opt.window);
  const double hi = std::min(t.back(), r.t_break + opt.window);

  // Where the lines cross inside the window the profile has a kink (a shock
  // resolved as a ramp): the intersection is the shock. Where they do not,
  // the profile steps between two nearly parallel lines and their
  // intersection is ill-conditioned, so the shock is the centre of the step:
  // the point that splits the window so that the step function (inner line,
  // then outer line) has the same integral as the data (exact for a
  // symmetric transition such as tanh, and an average over the window's
  // noise rather than one noisy crossing).
  const double tx = db != 0.0 ? (r.outer.a - r.inner.a) / db : std::numeric_limits<double>::infinity();
  if (std::isfinite(tx) && tx >= lo && tx <= hi) {
    r.kink = true;
    r.position = tx;
    r.sigma_position = std::sqrt(r.inner.var_at(tx) + r.outer.var_at(tx)) / std::abs(db);
  } else {
    int ilo = 0, ihi = n - 1;
    while (ilo < n - 1 && t[ilo] < lo) ++ilo;
    while (ihi > 0 && t[ihi] > hi) --ihi;
    if (ihi <= ilo) {
      r.position = r.t_break;
      r.sigma_position = opt.window;
    } else {
      const double a = t[ilo], b = t[ihi];
      double integral = 0.0, w2 = 0.0;
      for (int i = ilo; i <= ihi; ++i) {
        const double h_left = i > ilo ? t[i] - t[i - 1] : 0.0;
        const double h_right = i < ihi ? t[i + 1] - t[i] : 0.0;
        const double w = 0.5 * (h_left + h_right);  // trapezoid weight
        integral += w * f[i];
        w2 += w * w;
      }
      auto F = [&](double ts) { return line_integral(r.inner, a, ts) + line_integral(r.outer, ts, b); };
      // F is monotone in ts (F' = inner - outer, no sign change: the lines do
      // not cross in [a, b]); bisect, clamping to the window.
      double x0 = a, x1 = b;
      const bool rising = F(b) > F(a);
      for (int it = 0; it < kBisectIterations; ++it) {
        const double xm = 0.5 * (x0 + x1);
        if ((F(xm) < integral) == rising) x0 = xm; else x1 = xm;
      }
      r.position = 0.5 * (x0 + x1);
      const double d = std::abs(r.outer.at(r.position) - r.inner.at(r.position));
      const double var_i = var_scale * w2 + r.inner.var_at(r.position) * (r.position - a) * (r.position - a) +
                           r.outer.var_at(r.position) * (b - r.position) * (b - r.position);
      r.sigma_position = d > 0.0 ? std::sqrt(var_i) / d : opt.window;
    }
  }

  // Accept a jump only when the step or the change of slope stands out of
  // the noise, and the two lines beat one smooth curve clearly.
  const double k_sig = opt.noise_factor;
  const bool step_jump = std::abs(r.step) > k_sig * r.noise && std::abs(r.step) > k_sig * se_step;
  const bool slope_jump = std::abs(db) * opt.window > k_sig * r.noise && std::abs(db) > k_sig * se_db;
  const bool not_smooth = sse < kSmoothRejectRatio * quadratic_sse(t, f);
  r.accepted = (step_jump || slope_jump) && not_smooth;
  return r;
}

}  // namespace shockfit
