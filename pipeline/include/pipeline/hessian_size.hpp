#pragma once
// Isotropic target cell sizes from the Hessian of a scalar field on a
// lattice: the metric a CFD engineer adapts a grid with (docs/adapt.md).
//
//   lambda = max |eigenvalue| of the Hessian H of the field (central
//            differences after `smoothing_passes` 1-2-1 filters)
//   h      = (D lambda^(p/(p+1)))^(-1/2)   the L^p-optimal isotropic size
//            (interpolation error of a linear reconstruction measured in
//            L^p; p -> infinity gives h ~ lambda^(-1/2))
//   D      : the smallest size is h_min (lambda at its largest), or the
//            complexity sum(dA / h^2) meets a target number of cells
//   then h is clamped to [h_min, h_max] and graded:
//            h_i <= h_j + (growth - 1) |x_i - x_j| for every pair of
//            neighbouring lattice cells.
// Pure numerics on scene/lattice: nothing here knows where the field came from.
#include <optional>
#include <string>

#include "scene/lattice.hpp"

namespace pipeline {

// A lattice with the field "lambda" (>= 0). Cells whose 3x3 stencil meets a
// non-finite value (inside the body, cells no grid cell covers) get 0: no
// information, the far-field size. Cells on the lattice's outer ring take
// their inner neighbour's value.
scene::Lattice hessian_magnitude(const scene::Lattice& in, const std::string& field,
                                 int smoothing_passes);

struct SizeTarget {
  double h_min = 0, h_max = 0;  // lattice (scene) units
  double growth = 1.2;          // bound on the size ratio of neighbouring cells
  double norm_p = 2.0;          // the L^p norm the interpolation error is controlled in
  std::optional<double> cells;  // complexity to meet; unset: the smallest size is h_min
};

// A lattice with the field "h" (lattice units), from a hessian_magnitude
// lattice. InputError when sizes are not finite and 0 < h_min <= h_max,
// growth <= 1, or the target complexity lies outside what [h_min, h_max]
// allows on the lattice.
scene::Lattice size_from_hessian(const scene::Lattice& lambda, const SizeTarget& t);

// sum over lattice cells of dA / h^2: the number of cells a grid with the
// lattice's field "h" holds.
double lattice_complexity(const scene::Lattice& sizes);

// h_i <= h_j + (growth - 1) |x_i - x_j| over the 8 neighbours of every cell
// (forward and backward sweeps until nothing changes).
void limit_gradation(scene::Lattice& sizes, double growth);

}  // namespace pipeline
