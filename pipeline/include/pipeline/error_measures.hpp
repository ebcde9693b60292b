#pragma once
// Error measures of a finished CFD case against exact inviscid references,
// computed on the CFD cells themselves (docs/verdict.md):
// - attached wedge: the L1 error of density and of pressure against the
//   exact piecewise-constant solution's cell averages (a cell cut by the
//   exact shock line gets the area-weighted mix), normalised by the
//   free-stream value times the flow area;
// - any body: the L1 error of the total enthalpy over the forebody (the flow
//   ahead of the body's widest section), against the free stream's: a steady
//   inviscid adiabatic flow from a uniform stream keeps it constant
//   everywhere, across shocks too;
// - any body: the stagnation-point pressure against the Rayleigh pitot value,
//   extrapolated from the wall pressure of the stream-facing faces.
// The L1 measures carry the change between the last two written solutions as
// their uncertainty (the steady state's own flicker); the stagnation pressure
// the largest change over the last written times (its slower wander).
#include <array>
#include <string>
#include <vector>

#include "cfd/foam_reader.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "scene/vec2.hpp"

namespace pipeline {

struct MeasuredError {
  double value = scene::kNaN;
  double uncertainty = scene::kNaN;  // 95% half-width
};

struct CaseErrors {
  MeasuredError l1_density, l1_pressure;  // attached wedges only
  MeasuredError l1_total_enthalpy;        // forebody, any body
  MeasuredError stagnation_pressure;      // relative error against Rayleigh's pitot value
  double stagnation_pressure_ratio = scene::kNaN;  // measured p0 / p_inf
  double pitot_ratio = scene::kNaN;                // exact p0 / p_inf
  // Pressure drag coefficient of the modelled body surface: sum over body
  // faces of (p - p_inf) n_x A over q_inf = rho_inf U^2 / 2 times the body
  // length (per unit depth; a symmetric half model gives half the body's).
  double drag_coefficient = scene::kNaN;
  int solutions_compared = 0;  // written times used (2 gives an uncertainty)
  // Carbuncle check of the last solution (bow_shock_check.hpp): the largest
  // distance of the captured shock near the symmetry axis from the smooth
  // shape fitted off the axis, in cells; NaN where it cannot be measured.
  double shock_axis_deviation_cells = scene::kNaN;
};

// Area of the part of a polygon (any orientation) on the side n . p < 0 of
// the line through the origin with normal n.
double area_behind_line(const std::vector<scene::Vec2>& polygon, scene::Vec2 normal);

// L1 distance between a cell field and the exact two-state field (`behind`
// below the shock line through the origin at angle beta, `ahead` above it),
// over sum |A_c|, divided by `scale`.
double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, double beta,
                    double ahead, double behind, double scale);
// The same with each cell's share behind the line computed beforehand
// (behind_fractions), for several fields or times on one mesh.
std::vector<double> behind_fractions(const cfd::Mesh2D& mesh, double beta);
double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field,
                    const std::vector<double>& behind_fraction, double ahead, double behind,
                    double scale);

// Stagnation-point pressure from the body faces' fluid cells: a least-squares
// fit p = p0 + c theta^2 over the faces whose outward normal lies within
// kStagnationFitDeg of the stream direction (at least the three nearest),
// theta that angle; returns p0. Inviscid wall pressure is even in theta and
// stationary at the stagnation point (Newtonian: p0 cos^2 + p_inf sin^2), so
// the fit reaches theta = 0, where the nearest face's cell (half a cell off
// the axis) does not, and averages the cell-to-cell scatter of the faces.
double stagnation_pressure(const cfd::Mesh2D& mesh, const std::vector<double>& p);

// The measure named `name` (l1_density, l1_total_enthalpy or
// stagnation_pressure: the verdict's primary error) of a case's errors.
MeasuredError measure_named(const CaseErrors& e, const std::string& name);

// L1 distance of the total enthalpy H = gamma p / ((gamma - 1) rho) + |U|^2 / 2
// from the free stream's, relative to it, over sum |A_c| of the cells whose
// centre lies at x <= x_max (the forebody), in the CFD units (free stream
// p = T = 1, rho = gamma, |U| = Mach).
double forebody_total_enthalpy_l1(const cfd::Mesh2D& mesh, const std::vector<double>& rho,
                                  const std::vector<double>& p,
                                  const std::vector<std::array<double, 3>>& u, double mach,
                                  double gamma, double x_max);

// All measures that apply to the scene, from the case's last two written times.
CaseErrors measure_case_errors(const scene::Scene& s, const std::string& case_dir);

}  // namespace pipeline
