#pragma once
// Carbuncle check of a captured bow shock. An inviscid bow shock is smooth and
// crosses the symmetry axis at right angles, so near the axis its position
// follows x = a + b y^2. A carbuncle (the shock-capturing instability of
// strong shocks aligned with the cells) shows as a bump or a kink of the
// shock where it meets the axis, with an entropy and total-pressure defect
// along the stagnation streamline, which is exactly what the stagnation
// pressure reads. The check fits the parabola to the shock off the axis and
// reports how far the shock near the axis strays from it, in cells.
#include <limits>
#include <vector>

#include "cfd/foam_reader.hpp"
#include "scene/units.hpp"

namespace pipeline {

// A shock that strays more than this many cells from the fitted smooth shape
// at the axis is reported as a suspected carbuncle. The contour of a smooth
// captured shock on the project's quad-dominant Delaunay grids strays by
// under half a cell (measured: at most 0.45 cells over the 21 disc M4 and
// Apollo M5 case-study grids).
constexpr double kCarbuncleCells = 2.0;

struct AxisShockCheck {
  double deviation_cells = scene::kNaN;  // NaN: too few shock points
  double cell_size =
      scene::kNaN;  // sqrt of the mean cell area at the shock
  int axis_points = 0, fit_points = 0;
};

// Shock points are where the density crosses rho_mid between two cells
// sharing an edge (linear between their centres), upstream of x_max (the
// nose) and within |y| <= y_max. Points within three cells of the axis are
// tested against the parabola fitted to the others.
AxisShockCheck check_axis_shock(const cfd::Mesh2D& mesh, const std::vector<double>& rho,
                                double rho_mid, double x_max, double y_max);

}  // namespace pipeline
