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
// A jump must explain the profile near it better than one smooth curve can:
// over kLocalWindows shock windows either side of the breakpoint, the step
// model (inner line up to the shock position, outer line after it) must
// undercut one quadratic's squared error by more than noise_factor^2
// variances of an independent sample. A smooth profile (subsonic flow, an
// expansion) is a quadratic on that scale (its error is third order in the
// window, the lines' second order), so the step gains nothing; noise alone
// gains a few variances (a chi-square of few degrees of freedom); a jump J
// gains of order 0.05 J^2 per sample, less its few transition samples. The
// shock window stays in: left out, a smooth curve could bridge it freely.
constexpr double kLocalWindows = 6.0;
constexpr int kSmoothDegree = 2;
constexpr int kMinLocalPoints = 8;
constexpr int kBisectIterations = 100;
// Fewest samples that define a line on either side of the shock window.
constexpr int kMinLinePoints = 4;
constexpr double kGuardWindows = 2.0;
// A line shorter than this many windows is fitted as a level (no slope).
constexpr double kMinSlopeSpanWindows = 2.0;

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
// filled in later from the pooled noise. `level` fits a constant instead:
// over a short segment the slope is mostly noise, and extrapolating it to
// the shock would move the step more than the slope is worth.
Line fit_line(const std::vector<double>& t, const std::vector<double>& f, int i, int j, bool level,
              Eigen::Matrix2d& xtx_inv) {
  const int n = j - i;
  const int cols = level ? 1 : 2;
  Eigen::MatrixXd X(n, cols);
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) {
    X(k, 0) = 1.0;
    if (!level) X(k, 1) = t[i + k];
    y(k) = f[i + k];
  }
  const Eigen::VectorXd c = X.colPivHouseholderQr().solve(y);
  Line l;
  l.a = c(0);
  if (level) {
    xtx_inv = Eigen::Matrix2d::Zero();
    xtx_inv(0, 0) = 1.0 / n;
  } else {
    l.b = c(1);
    xtx_inv = (X.transpose() * X).inverse();
  }
  return l;
}

// Squared error of one polynomial of degree kSmoothDegree fitted to the
// samples `idx`: the smooth alternative to a jump.
double smooth_sse(const std::vector<double>& t, const std::vector<double>& f, const std::vector<int>& idx) {
  const auto n = static_cast<Eigen::Index>(idx.size());
  const double t0 = 0.5 * (t[idx.front()] + t[idx.back()]);
  const double scale = std::max(0.5 * (t[idx.back()] - t[idx.front()]), 1e-300);
  Eigen::MatrixXd X(n, kSmoothDegree + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double u = (t[idx[k]] - t0) / scale;
    double p = 1.0;
    for (int d = 0; d <= kSmoothDegree; ++d, p *= u) X(k, d) = p;
    y(k) = f[idx[k]];
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
  const double lo = std::max(t.front(), r.t_break - opt.window);
  const double hi = std::min(t.back(), r.t_break + opt.window);
  // The breakpoint search puts half the transition into each segment, which
  // tilts both lines towards the jump. Refit each line on its own side of the
  // shock window only, so the lines are the states on either side of the
  // shock. A jump too close to either end of the profile to leave such a
  // line is not measured.
  // The lines stay kGuardWindows windows clear of the breakpoint where the
  // profile is long enough (the tails of a wide transition would tilt them),
  // and at least one window clear.
  auto split = [&](double guard, int& in_end, int& out_begin) {
    in_end = static_cast<int>(std::lower_bound(t.begin(), t.end(), r.t_break - guard) - t.begin());
    out_begin = static_cast<int>(std::upper_bound(t.begin(), t.end(), r.t_break + guard) - t.begin());
    return in_end >= kMinLinePoints && n - out_begin >= kMinLinePoints;
  };
  int in_end = 0, out_begin = 0;
  const bool clear = split(kGuardWindows * opt.window, in_end, out_begin) || split(opt.window, in_end, out_begin);
  Eigen::Matrix2d inv_in, inv_out;
  const auto span = [&](int i, int j) { return t[j - 1] - t[i]; };
  const double min_span = kMinSlopeSpanWindows * opt.window;
  if (clear) {
    r.inner = fit_line(t, f, 0, in_end, span(0, in_end) < min_span, inv_in);
    r.outer = fit_line(t, f, out_begin, n, span(out_begin, n) < min_span, inv_out);
  } else {
    r.inner = fit_line(t, f, 0, k, false, inv_in);
    r.outer = fit_line(t, f, k, n, false, inv_out);
  }

  // Noise from the residuals outside the window (the transition is signal).
  std::vector<double> res;
  double sse = 0.0, fmax = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = f[i] - (i < k ? r.inner.at(t[i]) : r.outer.at(t[i]));
    if (t[i] < lo || t[i] > hi) res.push_back(std::abs(e));
    sse += e * e;
    fmax = std::max(fmax, std::abs(f[i]));
  }
  r.rms = std::sqrt(sse / n);
  if (res.empty()) return r;
  const auto mid = res.begin() + static_cast<long>(res.size() / 2);
  std::nth_element(res.begin(), mid, res.end());
  r.noise = std::max(kMadToSigma * *mid, kNoiseFloorRel * std::max(fmax, 1e-300));

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
  const double llo = r.t_break - kLocalWindows * opt.window, lhi = r.t_break + kLocalWindows * opt.window;
  std::vector<int> local;
  double local_sse = 0.0;
  for (int i = 0; i < n; ++i) {
    if (t[i] < llo || t[i] > lhi) continue;
    local.push_back(i);
    const double e = f[i] - (t[i] < r.position ? r.inner.at(t[i]) : r.outer.at(t[i]));
    local_sse += e * e;
  }
  const bool not_smooth = static_cast<int>(local.size()) >= kMinLocalPoints &&
                          smooth_sse(t, f, local) - local_sse > k_sig * k_sig * var_scale;
  r.accepted = clear && (step_jump || slope_jump) && not_smooth;
  r.rejected_by = r.accepted        ? ""
                  : !clear          ? "jump too close to an end of the profile"
                  : !(step_jump || slope_jump) ? "no step or change of slope above the noise"
                                    : "a smooth curve fits as well";
  return r;
}

}  // namespace shockfit
