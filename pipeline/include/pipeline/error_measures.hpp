#pragma once
// Error measures of a finished CFD case against exact inviscid references,
// computed on the CFD cells themselves (docs/verdict.md):
// - attached wedge: the L1 error of density and of pressure against the
//   exact piecewise-constant solution's cell averages (a cell cut by the
//   exact shock line gets the area-weighted mix), normalised by the
//   free-stream value times the flow area;
// - any body: the stagnation-point pressure against the Rayleigh pitot value.
// Each measure carries the change between the last two written solutions as
// its uncertainty (the steady state's own flicker).
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
  MeasuredError stagnation_pressure;      // relative error against Rayleigh's pitot value
  double stagnation_pressure_ratio = scene::kNaN;  // measured p0 / p_inf
  double pitot_ratio = scene::kNaN;                // exact p0 / p_inf
  // Pressure drag coefficient of the modelled body surface: sum over body
  // faces of (p - p_inf) n_x A over q_inf = rho_inf U^2 / 2 times the body
  // length (per unit depth; a symmetric half model gives half the body's).
  double drag_coefficient = scene::kNaN;
  int solutions_compared = 0;  // written times used (2 gives an uncertainty)
};

// Area of the part of a polygon (any orientation) on the side n . p < 0 of
// the line through the origin with normal n.
double area_behind_line(const std::vector<scene::Vec2>& polygon, scene::Vec2 normal);

// L1 distance between a cell field and the exact two-state field (`behind`
// below the shock line through the origin at angle beta, `ahead` above it),
// over sum |A_c|, divided by `scale`.
double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, double beta, double ahead,
                    double behind, double scale);
// The same with each cell's share behind the line computed beforehand
// (behind_fractions), for several fields or times on one mesh.
std::vector<double> behind_fractions(const cfd::Mesh2D& mesh, double beta);
double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, const std::vector<double>& behind_fraction,
                    double ahead, double behind, double scale);

// All measures that apply to the scene, from the case's last two written times.
CaseErrors measure_case_errors(const scene::Scene& s, const std::string& case_dir);

}  // namespace pipeline
