#pragma once
// Grid convergence of a scalar from three systematically refined grids
// (Roache 1998; ASME V&V 20): observed order, Richardson extrapolation and
// the grid convergence index. Oscillatory or divergent triples are reported
// as such, never forced.
#include <string>

namespace pipeline {

struct GridConvergence {
  bool monotone = false;    // (f3 - f2) and (f2 - f1) of one sign, shrinking
  double order = 0;         // observed p
  double extrapolated = 0;  // Richardson estimate of the grid-independent value
  double gci_fine = 0;      // relative, on the finest value, safety factor 1.25
  std::string note;         // why a triple was not usable
};

// f1 on the finest grid, f3 on the coarsest; r = h2/h1 = h3/h2 > 1.
GridConvergence richardson(double f1, double f2, double f3, double r);

}  // namespace pipeline
