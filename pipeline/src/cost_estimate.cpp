#include "pipeline/cost_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <numbers>
#include <sstream>

#include "granular/flow_setup.hpp"
#include "meshgen/mesh.hpp"
#include "pipeline/grid_runs.hpp"
#include "pipeline/precision_goal.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/predictors.hpp"
#include "pipeline/run.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"

namespace pipeline {

namespace {
// The model, each constant measured on this project's runs (docs/verdict.md,
// "Sizing a run"), fitted by bench/cost_model_check --fit on the 70 steady
// time-accurate grids of one `pipeline studies` run of the five case studies.
// The global time step, dt = max_co f h / (M + 2) for a grid of nominal size
// h: the smallest cells and the fastest waves set f. Medians: uniform grids
// 0.31 (their h_min cells include the free stream's, the fastest waves),
// clustered grids 0.38 (h_min cells only round the shock and the wall).
constexpr double kTimeStepFractionUniform = 0.31;
constexpr double kTimeStepFractionClustered = 0.38;
// Flow-through times to a measured steady state (the same fit's medians):
// attached wedges settle in about 2.2, blunt bodies (started at rest, a bow
// shock moving out) in about 7.8 under the former bow-shock gate, 1.37 times
// that (the median over seven disc and Apollo grids rerun, 1.27-1.58) since
// the standoff must hold still to 0.2% per flow-through; near-sonic bodies,
// whose flow leaves the domain subsonic, in about 25 (the Mach 1.3 disc: 29
// on a 1 R grid, ~20 on a 0.5 R grid).
constexpr double kFlowThroughsAttached = 2.2;
constexpr double kFlowThroughsBlunt = 10.7;
constexpr double kFlowThroughsSubsonicOutflow = 25.0;
// rhoCentralFoam serial cost (least squares on relative residuals, one
// timing's log sd 0.22): per step (the solver's fixed work, the monitor's
// reads), per cell-step, and per case (start-up, the last write).
constexpr double kCpuPerStep = 5.0e-5;
constexpr double kCpuPerCellStep = 1.19e-6;
constexpr double kCpuPerCase = 0.35;
// Mesh: meshgen's whole chain (gmsh in pieces, the polyMesh, checkMesh, the
// plots), a line through the same grids' meshing CPU seconds.
constexpr double kMeshCpuPerCell = 7.5e-5;
constexpr double kMeshCpuPerGrid = 0.7;
// The granular predictor's cost at the default particle count: the mean
// over the case studies at 4 averaged flow-through times (3.5 CPU s on wedge
// M3/10 to 18 on Apollo M5) after a detected warm-up of typically 1.75 (the
// median over 48 unseen wedges), per simulated flow-through time. It grows
// as particles^1.5: collisions per flow-through scale with the disks times
// the flow-through time, which grows with the domain's length in diameters,
// sqrt(particles) (wedge M3/10 at 4x the default particles: 41.6 against 4.7
// CPU s, 4^1.57), and with the replicas, each a whole run of its own (two
// measured; the disc M3.5 at four: 10.2 against 5.1 CPU s).
constexpr double kTypicalWarmupFlowThroughs = 1.75;
constexpr double kGranularPredictorCpuPerFlowThrough = 8.0 / (kTypicalWarmupFlowThroughs + 4.0);
// Where a band target typically stops: its minimum. Since its averaging is
// priced, every attached wedge run at the default and case-study sizes
// stopped there (docs/granular_flow.md, "The band's price"); before, the
// median over 48 runs on 16 unseen wedges was 4.25 (4.0-14.5).
constexpr double kTypicalBandAveraging = kBandMinAveraging;
constexpr double kGranularCpuParticleExponent = 1.5;

// Every grid's cells are meshgen's own estimate (meshgen::check_mesh_request:
// the size field integrated over the region meshgen meshes, strips counted
// exactly), the clustered grids' round a model of the shock each predictor
// reports, with the band it will carry (pipeline/src/predictor*.cpp):
// - correlation: its own shock, computed (the exact ray, Billig's shock);
// - granular: the exact oblique shock or Billig's shock, with the band a
//   granular run gets: its own interval combined with the calibration
//   table's out-of-sample scatter (none when the scene sets its
//   restitution). A run's own 95% angle interval is 0.6-1.2 deg on the
//   wedge case studies; a bow-shock station's own half-width is ~0.6% of its
//   distance from the body (disc M4 median 0.0057): the table's scatter
//   dominates both.
constexpr double kTypicalRunAngleCiDeg = 0.9;
constexpr double kTypicalStationCiRelative = 0.006;
// - the others (coarse CFD, adapted grids): the band the granular
//   predictor carries with the shipped table, as a half-angle of
//   hypot(0.9, 1.96 x 1.14) deg, and on bow shocks this fraction of
//   Billig's standoff (the median 95% half-width of the accepted stations in
//   the blunt case studies' granular bands: disc M4 0.47, Apollo M5 0.27).
constexpr double kTypicalBandHalfAngleDeg = 2.4;
constexpr double kTypicalBowBandRelative = 0.35;

ShockCurve granular_shock(const scene::Scene& s, const BandScatter& scatter) {
  if (const std::optional<double> beta = scene::attached_shock_beta(s))
    return apex_ray(scene::scene_domain(s), scene::make_body(*s.body).nose,
                    *beta * 180.0 / std::numbers::pi,
                    band_angle_half_width_deg(kTypicalRunAngleCiDeg, scatter.angle_deg));
  ShockCurve c = billig_bow_shock(s, 0.0);
  const scene::BodyGeometry body = scene::make_body(*s.body);
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const double d = std::abs(scene::signed_distance(body, c.points[i]));
    c.half_width[i] = band_bow_half_width(kTypicalStationCiRelative * d, d, scatter.bow_relative);
  }
  return c;
}

ShockCurve typical_shock(const scene::Scene& s, const std::string& predictor,
                         const BandScatter& scatter) {
  if (predictor == "correlation") return correlation_shock(s).curve;
  if (predictor == "granular") return granular_shock(s, scatter);
  if (const std::optional<double> beta = scene::attached_shock_beta(s))
    return apex_ray(scene::scene_domain(s), scene::make_body(*s.body).nose,
                    *beta * 180.0 / std::numbers::pi, kTypicalBandHalfAngleDeg);
  return billig_bow_shock(s, kTypicalBowBandRelative);
}

// The cells of the grid the pipeline asks meshgen for at `level` (grid_runs.cpp):
// uniform at h_min x level without a shock, clustered round it with one.
double grid_cells(const scene::Scene& s, double level, const ShockCurve* shock) {
  meshgen::MeshRequest r;
  r.uniform = shock == nullptr;
  r.h_min = s.mesh.h_min * level;
  r.h_max = (shock ? s.mesh.h_max : s.mesh.h_min) * level;
  if (shock) {
    r.shock_curve = shock->points;
    r.shock_ci = shock->half_width;
    if (s.mesh.h_body) r.h_body = *s.mesh.h_body * level;
  }
  return meshgen::check_mesh_request(s, r);
}

double steps_for(const scene::Scene& s, double h_min, bool clustered) {
  const scene::Domain d = scene::scene_domain(s);
  const double mach = s.freestream.mach;
  const double settle = scene::attached_shock_beta(s)       ? kFlowThroughsAttached
                        : scene::outflow_can_be_subsonic(s) ? kFlowThroughsSubsonicOutflow
                                                            : kFlowThroughsBlunt;
  const double flow_throughs = std::min(s.cfd.end_time, settle);
  const double f = clustered ? kTimeStepFractionClustered : kTimeStepFractionUniform;
  const double dt = s.cfd.max_co * f * h_min / (mach + 2.0);
  return flow_throughs * (d.width() / mach) / dt;
}

// The grid at `level`: clustered round `shock`, uniform without one.
GridEstimate grid(const scene::Scene& s, const std::string& name, double level,
                  const ShockCurve* shock) {
  GridEstimate g;
  g.name = name;
  g.cells = grid_cells(s, level, shock);
  g.steps = steps_for(s, s.mesh.h_min * scene::body_length(*s.body) * level, shock != nullptr);
  g.cpu_seconds = (kCpuPerStep + kCpuPerCellStep * g.cells) * g.steps + kCpuPerCase +
                  kMeshCpuPerCell * g.cells + kMeshCpuPerGrid;
  return g;
}
// The granular stage's CPU seconds, capped by granular.cpu_budget (its
// averaging stops before a chunk that would overrun it). Builds the flow
// setup first, so a particle count beyond what memory holds is refused here
// (InputError naming the key) before anything runs.
double granular_predictor_cpu(const scene::Scene& s) {
  const granular::FlowSetup f = granular::make_flow_setup(s);
  const scene::GranularParams& g = s.granular;
  const double averaging = g.target_from_band                              ? kTypicalBandAveraging
                           : precision_target(s) || g.target_from_standoff ? g.max_averaging
                                                                           : g.averaging;
  const double flow_throughs = g.warmup.value_or(kTypicalWarmupFlowThroughs) + averaging;
  const double cpu =
      kGranularPredictorCpuPerFlowThrough * flow_throughs *
      (static_cast<double>(g.replicas) / scene::kDefaultReplicas) *
      std::pow(f.expected_particles / scene::kDefaultFlowParticles, kGranularCpuParticleExponent);
  return s.granular.cpu_budget ? std::min(cpu, *s.granular.cpu_budget) : cpu;
}
}  // namespace

double clustered_finest_cpu(const scene::Scene& s, double angle_deg, double band_half_angle_deg) {
  if (!s.body || s.pipeline.levels.empty() || !std::isfinite(angle_deg) ||
      !std::isfinite(band_half_angle_deg))
    return scene::kNaN;
  const double level = *std::min_element(s.pipeline.levels.begin(), s.pipeline.levels.end());
  const ShockCurve shock = apex_ray(scene::scene_domain(s), scene::make_body(*s.body).nose,
                                    angle_deg, band_half_angle_deg);
  // A price is advice to the averaging, never a reason to fail the run it
  // serves: a grid the model cannot price leaves the averaging unpriced.
  try {
    return grid(s, level_name("clustered", level), level, &shock).cpu_seconds;
  } catch (const std::exception&) {
    return scene::kNaN;
  }
}

BandScatter band_scatter(const scene::Scene& s, const std::string& predictor,
                         const std::string& calibration_path) {
  if (predictor != "granular") return {};
  scene::Scene preview = s;  // the run applies the table to its own copy and reports it
  const AppliedCalibration c = apply_calibration(preview, calibration_path);
  return {c.angle_scatter_deg, c.bow_shock_relative_rms};
}

RunEstimate estimate_run(const scene::Scene& given, const std::string& predictor,
                         const BandScatter& scatter) {
  scene::Scene s = given;  // averaged as the run will (run_pipeline)
  if (predictor == "granular")
    default_to_band_averaging(s, scatter.angle_deg, scatter.bow_relative);
  RunEstimate e;
  for (const double level : s.pipeline.levels)
    e.grids.push_back(grid(s, level_name("uniform", level), level, nullptr));
  if (predictor != "none") {
    const ShockCurve shock = typical_shock(s, predictor, scatter);
    const std::string family = predictor == "granular" ? "clustered" : "clustered-" + predictor;
    for (const double level : s.pipeline.levels)
      e.grids.push_back(grid(s, level_name(family, level), level, &shock));
  }
  if (!scene::attached_shock_beta(s) && s.pipeline.reference_grid && !s.pipeline.levels.empty()) {
    const double level = reference_grid_level(s.pipeline);
    e.grids.push_back(grid(s, level_name("reference", level), level, nullptr));
  }
  e.predictor_cpu_seconds = predictor == "granular" ? granular_predictor_cpu(s) : 0.0;
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

std::optional<std::string> fit_default_sizes_to_budget(scene::Scene& s,
                                                       const std::string& predictor,
                                                       const BandScatter& scatter) {
  const double budget = s.pipeline.budget_cpu_seconds;
  // Sizes meshgen would refuse (a grid above its cell limit: a near-sonic
  // disc's large domain at the default h_min) are too fine, as sizes over
  // the budget are; an error the sizes cannot cure surfaces in the caller's
  // own estimate.
  const auto total = [&](const scene::Scene& t) {
    try {
      return estimate_run(t, predictor, scatter).total_cpu_seconds;
    } catch (const scene::InputError&) {
      return std::numeric_limits<double>::infinity();
    }
  };
  if (!s.mesh.sizes_default || total(s) <= budget) return std::nullopt;
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
  // Beyond the most it coarsens the defaults still cost too much (a
  // near-sonic body's domain is tens of body lengths across): it coarsens
  // that far and says so, and the budget check then refuses the run unless
  // --force-budget is given. Where meshgen would refuse even those sizes,
  // its own error (exit 2) says what to set.
  double cost = total(sized(kMaxCoarsening));  // the estimate at hi, the sizes chosen
  if (!std::isfinite(cost)) return std::nullopt;
  double lo = 1.0, hi = kMaxCoarsening;  // estimate(lo) > budget >= estimate(hi)
  if (cost <= budget) {
    for (int i = 0; i < kBisections && hi / lo > 1.0 + 1e-3; ++i) {
      const double mid = std::sqrt(lo * hi);
      const double at_mid = total(sized(mid));
      if (at_mid > budget) {
        lo = mid;
      } else {
        hi = mid;
        cost = at_mid;
      }
    }
  }
  const scene::Scene t = sized(hi);
  s.mesh.h_min = t.mesh.h_min;
  s.mesh.h_max = t.mesh.h_max;
  char line[400];
  std::snprintf(
      line, sizeof line,
      "pipeline: mesh.h_min = %g, mesh.h_max = %g body lengths (not in the scene: the defaults %g "
      "/ %g "
      "coarsened %.2fx %s the estimated %.0f CPU seconds %s pipeline.budget_cpu_seconds = %.0f)",
      s.mesh.h_min, s.mesh.h_max, defaults.h_min, defaults.h_max, s.mesh.h_min / defaults.h_min,
      cost <= budget ? "so" : "(the most it coarsens them), and still", cost,
      cost <= budget ? "fit" : "exceed", budget);
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
