#pragma once
// Exact contact-time solvers. Every prediction reduces to "when does a gap
// function f(t) first reach zero from above", with f the distance between
// the surfaces (or its square). The guards here are the engine's defence
// against round-off: a pair that is touching or overlapping by round-off and
// approaching collides NOW (dt = 0), so it can never tunnel; one that is
// touching and separating is not re-predicted at dt ~ 1e-16 (which would
// collide it twice).
#include <array>
#include <cmath>
#include <limits>

namespace granular::detail {

inline constexpr double kNever = std::numeric_limits<double>::infinity();
// A disk touching a surface with zero normal velocity while the force
// pushes it in (after a restitution-0 impact, or placed at rest) would
// "collide" now with a zero impulse, forever at the same instant. Instead
// it is let sink by this depth (in diameters, below the overlap tolerances) so
// that the next contact has a real approach speed: time always advances.
inline constexpr double kRestingSink = 1e-11;

// Smallest dt >= 0 at which f(dt) = c + b dt + a dt^2 reaches 0 while
// decreasing. c is the current gap (<= 0: touching or overlapped by
// round-off), b its rate of change, a half its acceleration.
inline double first_contact(double c, double b, double a) {
  if (c <= 0.0) {
    if (b < 0.0) return 0.0;  // approaching while touching: collide now
    // Separating (or at rest) while touching: it can only come back under
    // an acceleration towards the surface; it returns to the same gap
    // after -b/a (exact for the parabola), which avoids a spurious root at
    // dt ~ |c|/b from the round-off overlap.
    if (a < 0.0) return b > 0.0 ? -b / a : std::sqrt(kRestingSink / -a);
    return kNever;
  }
  if (a == 0.0) return b < 0.0 ? -c / b : kNever;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return kNever;
  // Stable quadratic roots (no cancellation): q = -(b + sign(b) sqrt(D))/2,
  // roots q/a and c/q. With c > 0 the first positive root is a downward
  // crossing.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double r1 = q / a;
  double r2 = q != 0.0 ? c / q : kNever;
  if (r1 < 0.0) r1 = kNever;
  if (r2 < 0.0) r2 = kNever;
  return r1 < r2 ? r1 : r2;
}

// Disk-disk (and disk-vertex without a force): |r + v dt| = sigma, with
// relative position r and velocity v at the reference time. sigma2 =
// sigma^2. Relative motion is linear even under a uniform force.
inline double disk_contact(double rx, double ry, double vx, double vy, double sigma2) {
  const double b = rx * vx + ry * vy;
  if (b >= 0.0) return kNever;  // separating: the gap only grows
  const double r2 = rx * rx + ry * ry;
  const double c = r2 - sigma2;
  if (c <= 0.0) return 0.0;  // touching / overlapped by round-off, approaching
  const double v2 = vx * vx + vy * vy;
  const double disc = b * b - v2 * c;
  if (disc < 0.0) return kNever;
  return c / (-b + std::sqrt(disc));  // the smaller root, without cancellation
}

// First root in (lo, hi] of a polynomial of degree <= 4 (coefficients low
// to high) where it crosses from > 0 to <= 0. Roots are isolated through the
// critical points (roots of the derivative, recursively), then bisected to
// full precision: slow but exact, and only vertices under gravity need it.
double first_downward_root(const std::array<double, 5>& c, int degree, double lo, double hi);

// Disk centre p (relative to a vertex), velocity v, acceleration g: first
// time |p + v t + g t^2/2| = radius with the distance decreasing, within
// [0, horizon].
double vertex_contact_accelerated(double px, double py, double vx, double vy, double gx,
                                  double gy, double radius, double horizon);

}  // namespace granular::detail
