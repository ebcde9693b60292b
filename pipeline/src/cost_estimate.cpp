#include "pipeline/cost_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "meshgen/mesh.hpp"
#include "meshgen/size_field.hpp"
#include "pipeline/grid_runs.hpp"
#include "pipeline/predictor.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"

namespace pipeline {

namespace {
// The model, each constant measured on this project's runs (docs/verdict.md):
// gmsh's quad-dominant Delaunay grids hold about 1.5 cells per h^2 of area.
constexpr double kCellsPerH2 = 1.5;
// The global time step, dt = max_co f h / (M + 2) for a grid of nominal
// size h: f = 0.36 is the median over 100 recorded time-accurate runs of the
// case studies (0.26-0.5: the smallest cell and the fastest waves behind the
// shock set it), fitted by bench/cost_model_check --fit.
constexpr double kTimeStepFraction = 0.36;
// Flow-through times to a measured steady state (the same fit's medians):
// attached wedges settle in about 2.4, blunt bodies (started at rest, a bow
// shock moving out) in about 8.
constexpr double kFlowThroughsAttached = 2.4;
constexpr double kFlowThroughsBlunt = 8.0;
// rhoCentralFoam serial cost, fitted on the same runs (2 shared cores): per
// step (the solver's fixed work, the monitor's reads) and per cell-step.
constexpr double kCpuPerStep = 3.4e-4;
constexpr double kCpuPerCellStep = 1.5e-6;
constexpr double kCpuPerCase = 1.5;
// Mesh: meshgen's whole chain (gmsh in pieces, the polyMesh, checkMesh, the
// plots) measured at 9.2 CPU s for 108k cells (docs/meshgen.md).
constexpr double kMeshCpuPerCell = 8.5e-5;
constexpr double kMeshCpuPerGrid = 1.0;
// A clustered grid grades from h_min to h_max at ratio `growth`: per unit
// shock length and side, the graded layers hold sum 1/h_k ~ 1/(h_min (1 - 1/growth)) cells.
// The granular predictor's cost on the case studies (CPU seconds).
constexpr double kGranularPredictorCpu = 30.0;

double fluid_area(const scene::Scene& s) {
  const scene::Domain d = scene::scene_domain(s);
  const auto g = scene::make_body(*s.body);
  double a = 0;
  const auto& p = g.polyline;
  for (std::size_t i = 0; i < p.size(); ++i) a += scene::cross(p[i], p[(i + 1) % p.size()]);
  const double body = 0.5 * std::abs(a) * (d.symmetric ? 0.5 : 1.0);
  return std::max(0.0, d.width() * d.height() - body);
}

// Length of the shock inside the domain: the oblique line for attached
// wedges, else about the domain's height (a bow shock bending downstream).
double shock_length(const scene::Scene& s) {
  const scene::Domain d = scene::scene_domain(s);
  if (const auto beta = scene::attached_shock_beta(s)) {
    const double x_end = std::min(d.xmax, d.ymax / std::tan(*beta));
    return x_end / std::cos(*beta);
  }
  constexpr double kBowLengthPerHeight = 1.3;
  return kBowLengthPerHeight * d.height();
}

// Length of the body surface inside the domain (scene units).
double body_surface_length(const scene::Scene& s) {
  const std::vector<scene::Vec2> outline = scene::clipped_outline(scene::make_body(*s.body), scene::scene_domain(s));
  double len = 0.0;
  for (std::size_t i = 0; i + 1 < outline.size(); ++i) len += scene::norm(outline[i + 1] - outline[i]);
  return len;
}

// Where an attached shock is meshed in shock-aligned strips
// (scene::band_anisotropy), the clustered grid's cells are meshgen's own
// estimate (strips counted, the grid round them integrated) round the exact
// oblique shock, its band the half-angle a granular prediction typically
// carries: the shipped table's 1.96 x 1.14 deg out-of-sample scatter with a
// 0.6-1.2 deg run interval in quadrature (docs/calibration.md).
constexpr double kTypicalBandHalfAngleDeg = 2.4;

std::optional<double> strip_grid_cells(const scene::Scene& s, double level) {
  const std::optional<double> beta = scene::attached_shock_beta(s);
  if (!beta || !(scene::band_anisotropy(s) > 1.0)) return std::nullopt;
  const ShockCurve ray = apex_ray(scene::scene_domain(s), scene::make_body(*s.body).nose,
                                  *beta * 180.0 / std::numbers::pi, kTypicalBandHalfAngleDeg);
  meshgen::MeshRequest r;
  r.shock_curve = ray.points;
  r.shock_ci = ray.half_width;
  r.h_min = s.mesh.h_min * level;
  r.h_max = s.mesh.h_max * level;
  return meshgen::check_mesh_request(s, r);
}

double steps_for(const scene::Scene& s, double h_min) {
  const scene::Domain d = scene::scene_domain(s);
  const double mach = s.freestream.mach;
  const double flow_throughs = std::min(s.cfd.end_time,
                                        scene::attached_shock_beta(s) ? kFlowThroughsAttached : kFlowThroughsBlunt);
  const double dt = s.cfd.max_co * kTimeStepFraction * h_min / (mach + 2.0);
  return flow_throughs * (d.width() / mach) / dt;
}

GridEstimate grid(const scene::Scene& s, const std::string& name, double cells, double h_min) {
  GridEstimate g;
  g.name = name;
  g.cells = cells;
  g.steps = steps_for(s, h_min);
  g.cpu_seconds = (kCpuPerStep + kCpuPerCellStep * g.cells) * g.steps + kCpuPerCase + kMeshCpuPerCell * cells + kMeshCpuPerGrid;
  return g;
}
}  // namespace

RunEstimate estimate_run(const scene::Scene& s, const std::string& predictor) {
  RunEstimate e;
  const double L = scene::body_length(*s.body);
  const double area = fluid_area(s), shock = shock_length(s), body = body_surface_length(s);
  const std::optional<double> band =
      s.mesh.band_width ? std::optional<double>(*s.mesh.band_width * L) : std::nullopt;
  for (const double level : s.pipeline.levels) {
    const double h = s.mesh.h_min * L * level;
    e.grids.push_back(grid(s, level_name("uniform", level), kCellsPerH2 * area / (h * h), h));
  }
  if (predictor != "none")
    for (const double level : s.pipeline.levels) {
      const double h = s.mesh.h_min * L * level, H = s.mesh.h_max * L * level;
      const double w = meshgen::band_half_width(band, h);
      const double graded = 2.0 * shock / (h * (1.0 - 1.0 / s.mesh.growth));
      // meshgen's body rule, h = h_body + (growth - 1) d from the wall (h_body = h_min unless
      // mesh.h_body says otherwise): per unit wall length its layers hold
      // int (1/h^2 - 1/H^2) dd = (1/h_body - 1/H)/(growth - 1) - (H - h_body)/((growth - 1) H^2)
      // cells beyond the far field's (the shock band overlaps them near an apex: an overestimate).
      const double h_body = meshgen::body_cell_size(
          s.mesh.h_body ? std::optional<double>(*s.mesh.h_body * L * level) : std::nullopt, h, H);
      const double slope = s.mesh.growth - 1.0;
      const double at_body = body * ((1.0 / h_body - 1.0 / H) / slope - (H - h_body) / (slope * H * H));
      const double cells = strip_grid_cells(s, level).value_or(
          kCellsPerH2 * (2.0 * w * shock / (h * h) + graded + at_body + area / (H * H)));
      e.grids.push_back(grid(s, level_name(predictor == "granular" ? "clustered" : "clustered-" + predictor, level),
                             cells, h));
    }
  if (!scene::attached_shock_beta(s) && s.pipeline.reference_grid && !s.pipeline.levels.empty()) {
    const double level = reference_grid_level(s.pipeline);
    const double h = s.mesh.h_min * L * level;
    e.grids.push_back(grid(s, level_name("reference", level), kCellsPerH2 * area / (h * h), h));
  }
  e.predictor_cpu_seconds = predictor == "granular" ? kGranularPredictorCpu : 0.0;
  e.total_cpu_seconds = e.predictor_cpu_seconds;
  for (const auto& g : e.grids) e.total_cpu_seconds += g.cpu_seconds;
  return e;
}

std::string format_estimate(const RunEstimate& e, double budget) {
  std::ostringstream os;
  os << "# estimated cost (model in docs/verdict.md; expect +-50%)\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %12s %12s %14s\n", "grid", "cells", "steps", "CPU seconds");
  os << line;
  for (const auto& g : e.grids) {
    std::snprintf(line, sizeof line, "%-28s %12.0f %12.0f %14.1f\n", g.name.c_str(), g.cells, g.steps, g.cpu_seconds);
    os << line;
  }
  std::snprintf(line, sizeof line, "%-28s %12s %12s %14.1f\n", "predictor", "", "", e.predictor_cpu_seconds);
  os << line;
  std::snprintf(line, sizeof line, "%-28s %12s %12s %14.1f  (%.2f CPU hours; budget %.0f s)\n", "total", "", "",
                e.total_cpu_seconds, e.total_cpu_seconds / 3600.0, budget);
  os << line;
  return os.str();
}

std::optional<std::string> fit_default_sizes_to_budget(scene::Scene& s, const std::string& predictor) {
  const double budget = s.pipeline.budget_cpu_seconds;
  if (!s.mesh.sizes_default || estimate_run(s, predictor).total_cpu_seconds <= budget) return std::nullopt;
  // Cells, and with them the cost, fall steeply with h (about h^-3), so a
  // factor of 10 covers default scenes estimated up to ~1000 budgets.
  constexpr double kMaxCoarsening = 10.0;
  constexpr int kBisections = 40;
  const scene::MeshParams defaults = s.mesh;
  const auto round2 = [](double v) {
    const double p = std::pow(10.0, std::floor(std::log10(v)) - 1.0);
    return std::ceil(v / p) * p;  // up: the rounded sizes stay within the budget
  };
  const auto sized = [&](double k) {
    scene::Scene t = s;
    t.mesh.h_min = round2(defaults.h_min * k);
    t.mesh.h_max = round2(defaults.h_max * k);
    return t;
  };
  if (estimate_run(sized(kMaxCoarsening), predictor).total_cpu_seconds > budget) return std::nullopt;
  double lo = 1.0, hi = kMaxCoarsening;  // estimate(lo) > budget >= estimate(hi)
  for (int i = 0; i < kBisections && hi / lo > 1.0 + 1e-3; ++i) {
    const double mid = std::sqrt(lo * hi);
    (estimate_run(sized(mid), predictor).total_cpu_seconds > budget ? lo : hi) = mid;
  }
  const scene::Scene t = sized(hi);
  s.mesh.h_min = t.mesh.h_min;
  s.mesh.h_max = t.mesh.h_max;
  char line[320];
  std::snprintf(line, sizeof line,
                "pipeline: mesh.h_min = %g, mesh.h_max = %g body lengths (not in the scene: the defaults %g / %g "
                "coarsened %.2fx so the estimated %.0f CPU seconds fit pipeline.budget_cpu_seconds = %.0f)",
                s.mesh.h_min, s.mesh.h_max, defaults.h_min, defaults.h_max, s.mesh.h_min / defaults.h_min,
                estimate_run(s, predictor).total_cpu_seconds, budget);
  return std::string(line);
}

void check_budget(const scene::Scene& s, const RunEstimate& e, bool force_budget) {
  if (force_budget || e.total_cpu_seconds <= s.pipeline.budget_cpu_seconds) return;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                ": key 'pipeline.budget_cpu_seconds': the run is estimated at %.0f CPU seconds (%.1f CPU hours), over "
                "the budget of %.0f; see the grids with --dry-run, coarsen mesh.h_min or pipeline.levels, raise the "
                "budget, or pass --force-budget",
                e.total_cpu_seconds, e.total_cpu_seconds / 3600.0, s.pipeline.budget_cpu_seconds);
  throw scene::InputError(s.source_file + buf);
}

}  // namespace pipeline
