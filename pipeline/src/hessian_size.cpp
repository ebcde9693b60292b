#include "pipeline/hessian_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scene/errors.hpp"

namespace pipeline {

namespace {

// Gradation sweeps stop when no size moves by more than this fraction (the
// limit is a fixed point: a few sweeps reach it on smooth fields).
constexpr double kGradationSlack = 1e-12;
constexpr int kMaxGradationSweeps = 1000;
// Complexity targets are met to this relative precision by bisection on D.
constexpr double kComplexityPrecision = 1e-4;
constexpr int kMaxBisections = 200;

std::vector<double> smooth_once(const scene::Lattice& lat, const std::vector<double>& f) {
  // 1-2-1 in each direction (3x3 binomial), over finite neighbours only,
  // weights renormalised; non-finite cells stay as they are.
  std::vector<double> out = f;
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) {
      if (!std::isfinite(f[lat.index(i, j)])) continue;
      double sum = 0, weight = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= lat.nx || jj >= lat.ny) continue;
          const double v = f[lat.index(ii, jj)];
          if (!std::isfinite(v)) continue;
          const double w = (di == 0 ? 2.0 : 1.0) * (dj == 0 ? 2.0 : 1.0);
          sum += w * v;
          weight += w;
        }
      out[lat.index(i, j)] = sum / weight;
    }
  return out;
}

// Largest |eigenvalue| of [[a, b], [b, c]].
double max_abs_eigenvalue(double a, double b, double c) {
  return 0.5 * std::abs(a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b);
}

void check_target(const SizeTarget& t) {
  if (!std::isfinite(t.h_min) || !std::isfinite(t.h_max) || !(t.h_min > 0) || t.h_min > t.h_max)
    throw scene::InputError("size field: h_min and h_max must be finite with 0 < h_min <= h_max");
  if (!(t.growth > 1.0) || !std::isfinite(t.growth))
    throw scene::InputError("size field: growth must exceed 1");
  if (!(t.norm_p > 0) || !std::isfinite(t.norm_p))
    throw scene::InputError("size field: the norm p must be positive");
  if (t.cells && !(std::isfinite(*t.cells) && *t.cells > 0))
    throw scene::InputError("size field: the target complexity must be a positive number of cells");
}

// Sizes for a given D: h = (D lambda^q)^(-1/2), clamped, graded.
scene::Lattice sizes_for(const scene::Lattice& lambda, const SizeTarget& t, double q, double D) {
  scene::Lattice out(lambda.nx, lambda.ny, lambda.x0, lambda.y0, lambda.dx, lambda.dy);
  const auto& lam = lambda.field("lambda");
  auto& h = out.add("h", t.h_max);
  for (std::size_t k = 0; k < h.size(); ++k) {
    const double m = D * std::pow(lam[k], q);
    h[k] = m > 0 ? std::clamp(1.0 / std::sqrt(m), t.h_min, t.h_max) : t.h_max;
  }
  limit_gradation(out, t.growth);
  return out;
}

}  // namespace

scene::Lattice hessian_magnitude(const scene::Lattice& in, const std::string& field,
                                 int smoothing_passes) {
  std::vector<double> f = in.field(field);
  for (int k = 0; k < smoothing_passes; ++k) f = smooth_once(in, f);
  scene::Lattice out(in.nx, in.ny, in.x0, in.y0, in.dx, in.dy);
  auto& lam = out.add("lambda", 0.0);
  const double dx2 = in.dx * in.dx, dy2 = in.dy * in.dy, dxdy4 = 4.0 * in.dx * in.dy;
  // Interior cells first; the outer ring copies its inner neighbour.
  for (int j = 1; j + 1 < in.ny; ++j)
    for (int i = 1; i + 1 < in.nx; ++i) {
      const auto v = [&](int di, int dj) { return f[in.index(i + di, j + dj)]; };
      bool finite = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) finite = finite && std::isfinite(v(di, dj));
      if (!finite) continue;
      const double fxx = (v(1, 0) - 2.0 * v(0, 0) + v(-1, 0)) / dx2;
      const double fyy = (v(0, 1) - 2.0 * v(0, 0) + v(0, -1)) / dy2;
      const double fxy = (v(1, 1) - v(1, -1) - v(-1, 1) + v(-1, -1)) / dxdy4;
      lam[in.index(i, j)] = max_abs_eigenvalue(fxx, fxy, fyy);
    }
  if (in.nx >= 3 && in.ny >= 3)
    for (int j = 0; j < in.ny; ++j)
      for (int i = 0; i < in.nx; ++i) {
        if (i > 0 && j > 0 && i + 1 < in.nx && j + 1 < in.ny) continue;
        lam[in.index(i, j)] =
            lam[in.index(std::clamp(i, 1, in.nx - 2), std::clamp(j, 1, in.ny - 2))];
      }
  return out;
}

void limit_gradation(scene::Lattice& sizes, double growth) {
  (void)sizes.field("h");  // InputError naming the fields there are
  std::vector<double>& h = sizes.fields.at("h");
  const double slope = growth - 1.0;
  const double diag = std::hypot(sizes.dx, sizes.dy);
  const int nx = sizes.nx, ny = sizes.ny;
  // Relax cell (i, j) against the neighbour (i + di, j + dj) at distance d.
  const auto relax = [&](int i, int j, int di, int dj, double d) {
    const int ii = i + di, jj = j + dj;
    if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) return false;
    double& hk = h[sizes.index(i, j)];
    const double bound = h[sizes.index(ii, jj)] + slope * d;
    if (!(bound < hk)) return false;
    const bool moved = bound < hk * (1.0 - kGradationSlack);
    hk = bound;
    return moved;
  };
  for (int sweep = 0; sweep < kMaxGradationSweeps; ++sweep) {
    bool moved = false;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        moved |= relax(i, j, -1, 0, sizes.dx);
        moved |= relax(i, j, 0, -1, sizes.dy);
        moved |= relax(i, j, -1, -1, diag);
        moved |= relax(i, j, 1, -1, diag);
      }
    for (int j = ny - 1; j >= 0; --j)
      for (int i = nx - 1; i >= 0; --i) {
        moved |= relax(i, j, 1, 0, sizes.dx);
        moved |= relax(i, j, 0, 1, sizes.dy);
        moved |= relax(i, j, 1, 1, diag);
        moved |= relax(i, j, -1, 1, diag);
      }
    if (!moved) return;
  }
}

double lattice_complexity(const scene::Lattice& sizes) {
  const auto& h = sizes.field("h");
  double n = 0;
  for (const double v : h) n += sizes.dx * sizes.dy / (v * v);
  return n;
}

scene::Lattice size_from_hessian(const scene::Lattice& lambda, const SizeTarget& t) {
  check_target(t);
  const double q = t.norm_p / (t.norm_p + 1.0);
  const auto& lam = lambda.field("lambda");
  const double lam_max = lam.empty() ? 0.0 : *std::max_element(lam.begin(), lam.end());
  if (!(lam_max > 0)) {
    // A uniform field: nothing to adapt to.
    scene::Lattice out(lambda.nx, lambda.ny, lambda.x0, lambda.y0, lambda.dx, lambda.dy);
    out.add("h", t.h_max);
    return out;
  }
  // D at which the largest lambda gets exactly h_min.
  const double d_hmin = 1.0 / (t.h_min * t.h_min * std::pow(lam_max, q));
  if (!t.cells) return sizes_for(lambda, t, q, d_hmin);
  // Complexity grows with D (sizes shrink); it runs from all-h_max to all-h_min.
  const double area = lambda.nx * lambda.dx * lambda.ny * lambda.dy;
  const double n_lo = area / (t.h_max * t.h_max), n_hi = area / (t.h_min * t.h_min);
  if (*t.cells < n_lo || *t.cells > n_hi)
    throw scene::InputError("size field: a target of " + std::to_string(*t.cells) +
                            " cells lies outside the " + std::to_string(n_lo) + " .. " +
                            std::to_string(n_hi) + " that [h_min, h_max] allows");
  double lo = d_hmin, hi = d_hmin;
  int guard = 0;
  while (lattice_complexity(sizes_for(lambda, t, q, lo)) > *t.cells && ++guard < kMaxBisections)
    lo *= 0.5;
  while (lattice_complexity(sizes_for(lambda, t, q, hi)) < *t.cells && ++guard < kMaxBisections)
    hi *= 2.0;
  for (int it = 0; it < kMaxBisections && hi / lo > 1.0 + kComplexityPrecision; ++it) {
    const double mid = std::sqrt(lo * hi);
    (lattice_complexity(sizes_for(lambda, t, q, mid)) < *t.cells ? lo : hi) = mid;
  }
  return sizes_for(lambda, t, q, std::sqrt(lo * hi));
}

}  // namespace pipeline
