#include "pipeline/grid_convergence.hpp"

#include <cmath>
#include <limits>

#include "scene/units.hpp"

namespace pipeline {

namespace {
// Roache's safety factor for a three-grid study with an observed order.
constexpr double kSafetyThreeGrids = 1.25;
}  // namespace

GridConvergence richardson(double f1, double f2, double f3, double r) {
  GridConvergence g;
  using scene::kNaN;
  g.order = g.extrapolated = g.gci_fine = kNaN;
  if (!(r > 1) || !std::isfinite(f1) || !std::isfinite(f2) || !std::isfinite(f3)) {
    g.note = "missing value or refinement ratio <= 1";
    return g;
  }
  const double d21 = f2 - f1, d32 = f3 - f2;
  if (d21 == 0 && d32 == 0) {
    g.monotone = true;
    g.order = std::numeric_limits<double>::infinity();
    g.extrapolated = f1;
    g.gci_fine = 0;
    g.note = "identical on all three grids";
    return g;
  }
  if (d21 * d32 <= 0) {
    g.note = "oscillatory: the differences change sign";
    return g;
  }
  const double p = std::log(d32 / d21) / std::log(r);
  if (!(p > 0)) {
    g.note = "divergent: the difference grows with refinement";
    return g;
  }
  g.monotone = true;
  g.order = p;
  const double rp1 = std::pow(r, p) - 1.0;
  g.extrapolated = f1 + (f1 - f2) / rp1;
  g.gci_fine = f1 != 0 ? kSafetyThreeGrids * std::abs(d21 / f1) / rp1 : kNaN;
  return g;
}

}  // namespace pipeline
