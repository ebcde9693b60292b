#include "contact_time.hpp"

#include <algorithm>
#include <vector>

namespace granular::detail {

namespace {

double eval(const std::array<double, 5>& c, int degree, double t) {
  double s = 0.0;
  for (int k = degree; k >= 0; --k) s = s * t + c[static_cast<std::size_t>(k)];
  return s;
}

// Bisection bound: 200 halvings take any double interval to adjacent doubles.
constexpr int kMaxBisections = 200;

double bisect(const std::array<double, 5>& c, int degree, double lo, double hi) {
  // Invariant: f(lo) > 0 >= f(hi).
  for (int it = 0; it < kMaxBisections; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (eval(c, degree, mid) > 0.0) lo = mid; else hi = mid;
  }
  return hi;  // the side where the gap is already closed: never late
}

// All sign-change points of the polynomial in [lo, hi], sorted.
void roots_in(const std::array<double, 5>& c, int degree, double lo, double hi,
              std::vector<double>& out) {
  if (degree <= 0) return;
  if (degree == 1) {
    if (c[1] != 0.0) {
      const double r = -c[0] / c[1];
      if (r > lo && r < hi) out.push_back(r);
    }
    return;
  }
  std::array<double, 5> d{};
  for (int k = 1; k <= degree; ++k) d[static_cast<std::size_t>(k - 1)] = k * c[static_cast<std::size_t>(k)];
  std::vector<double> crit;
  roots_in(d, degree - 1, lo, hi, crit);
  double a = lo;
  double fa = eval(c, degree, a);
  crit.push_back(hi);
  for (const double b : crit) {
    const double fb = eval(c, degree, b);
    if ((fa > 0.0) != (fb > 0.0)) {
      // Bisect on the monotone piece [a, b] for the sign change.
      double x = a, y = b;
      const bool up = fb > 0.0;
      for (int it = 0; it < kMaxBisections; ++it) {
        const double m = 0.5 * (x + y);
        if (m <= x || m >= y) break;
        if ((eval(c, degree, m) > 0.0) == up) y = m; else x = m;
      }
      out.push_back(y);
    }
    a = b;
    fa = fb;
  }
}

}  // namespace

double first_downward_root(const std::array<double, 5>& c, int degree, double lo, double hi) {
  if (!(hi > lo)) return kNever;
  std::array<double, 5> d{};
  for (int k = 1; k <= degree; ++k) d[static_cast<std::size_t>(k - 1)] = k * c[static_cast<std::size_t>(k)];
  std::vector<double> pts;
  roots_in(d, degree - 1, lo, hi, pts);  // monotone pieces of f
  pts.push_back(hi);
  double a = lo;
  double fa = eval(c, degree, a);
  for (const double b : pts) {
    const double fb = eval(c, degree, b);
    if (fa > 0.0 && fb <= 0.0) return bisect(c, degree, a, b);
    a = b;
    fa = fb;
  }
  return kNever;
}

double vertex_contact_accelerated(double px, double py, double vx, double vy, double gx,
                                  double gy, double radius, double horizon) {
  // f(t) = |p + v t + g t^2 / 2|^2 - R^2, a quartic.
  const double hx = 0.5 * gx, hy = 0.5 * gy;
  std::array<double, 5> c{};
  c[0] = px * px + py * py - radius * radius;
  c[1] = 2.0 * (px * vx + py * vy);
  c[2] = vx * vx + vy * vy + 2.0 * (px * hx + py * hy);
  c[3] = 2.0 * (vx * hx + vy * hy);
  c[4] = hx * hx + hy * hy;
  if (c[0] <= 0.0) {
    // Touching (or overlapped by round-off). Approaching: collide now.
    if (c[1] < 0.0) return 0.0;
    // At rest on the vertex and pushed in: sink by kRestingSink (f ~ c2 t^2).
    if (c[1] == 0.0 && c[2] < 0.0) return std::sqrt(kRestingSink / -c[2]);
    // Separating: f(t) - f(0) = t * (c1 + c2 t + c3 t^2 + c4 t^3). The disk
    // comes back to the same gap where the cubic factor turns negative;
    // dividing out the root at t = 0 avoids a spurious round-off root there.
    const std::array<double, 5> cubic{c[1], c[2], c[3], c[4], 0.0};
    if (c[1] == 0.0) return kNever;
    return first_downward_root(cubic, 3, 0.0, horizon);
  }
  return first_downward_root(c, 4, 0.0, horizon);
}

}  // namespace granular::detail
