#include "pipeline/grid_runs.hpp"

#include <algorithm>
#include <cmath>

#include "cfd/run_case.hpp"
#include "meshgen/mesh.hpp"
#include "json_fields.hpp"
#include "pipeline/error_measures.hpp"
#include "scene/body_traits.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/progress.hpp"
#include "scene/shock_kind.hpp"
#include "scene/units.hpp"
#include "shockfit/locate.hpp"

namespace pipeline {

namespace {

using scene::kNaN;

bool is_clustered(const std::string& family) { return family.rfind("clustered", 0) == 0; }

// rhoCentralFoam with a limited reconstruction spreads a shock over about
// this many cells; the shock window (half-width) spans this many shock widths.
constexpr double kCfdShockCells = 3.0;
constexpr double kWindowPerShockWidth = 1.25;

scene::Scene cfd_shockfit_scene(const scene::Scene& s, double h_shock) {
  scene::Scene c = s;
  const scene::Domain d = scene::scene_domain(s);
  const double dx = std::max(d.width() / s.granular.lattice_nx, d.height() / s.granular.lattice_ny);
  c.shockfit.window = std::max(s.shockfit.window, kWindowPerShockWidth * kCfdShockCells * h_shock / dx);
  c.shockfit.min_samples = 0;  // CFD lattices carry no sample counts
  return c;
}

double shock_value(const shockfit::ShockResult& r) {
  if (r.shock == scene::ShockKind::attached) return r.shock_angle_deg;
  if (r.shock == scene::ShockKind::detached) return r.standoff;
  return kNaN;
}
double shock_ci(const shockfit::ShockResult& r) {
  if (r.shock == scene::ShockKind::attached) return r.shock_angle_ci_deg;
  if (r.shock == scene::ShockKind::detached) return r.standoff_ci;
  return kNaN;
}

// The request of a clustered grid: the band round the shock curve, or the
// level's size field when the prediction gives them.
meshgen::MeshRequest clustered_request(const ShockInput& shock, double level) {
  if (shock.size_fields.empty()) return meshgen::request_from_shock_csv(shock.shock_csv);
  for (const auto& [l, path] : shock.size_fields)
    if (same_level(l, level)) return meshgen::request_from_size_field(path);
  throw scene::InputError("the prediction has no size field for level " + std::to_string(level));
}

}  // namespace

void check_interrupt(const std::string& where) {
  if (scene::interrupted())
    throw scene::RunError("interrupted during " + where + "; finished stages are kept, rerun to resume");
}

std::string level_name(const std::string& family, double level) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s_h%g", family.c_str(), level);
  return buf;
}

bool same_level(double a, double b) {
  constexpr double kLevelSlack = 1e-9;
  return std::abs(a - b) <= kLevelSlack * std::max(std::abs(a), std::abs(b));
}

double reference_grid_level(const scene::PipelineParams& p) {
  if (p.reference_level) return *p.reference_level;
  if (p.levels.empty()) return 0.5;
  const double finest = *std::min_element(p.levels.begin(), p.levels.end());
  auto has = [&](double l) { return std::any_of(p.levels.begin(), p.levels.end(), [&](double x) { return same_level(x, l); }); };
  double best = 0.5 * finest;
  for (const double a : p.levels) {
    const double l = 0.5 * a;
    if (l < finest && !same_level(l, finest) && has(2.0 * a) && l > best) best = l;
  }
  return best;
}

namespace {
scene::Scene with_robust_cfd(const scene::Scene& s) {
  scene::Scene r = s;
  std::string what;
  r.cfd = cfd::robust_settings(s.cfd, what);
  return r;
}
scene::Scene with_isotropic_band(const scene::Scene& s) {
  scene::Scene r = s;
  r.mesh.anisotropy = 1.0;
  return r;
}

// One spelling for a case's scheme and the robust one, which are compared.
std::string scheme_name(const std::string& flux, const std::string& limiter) {
  return flux.empty() && limiter.empty() ? "" : flux + "/" + limiter;
}
}  // namespace

std::string case_scheme(const nlohmann::json& cfd_summary) {
  return scheme_name(cfd_summary.value("flux_scheme", ""), cfd_summary.value("limiter", ""));
}

GridRunner::GridRunner(const scene::Scene& s, const std::string& out_dir, int np,
                       std::set<std::string> force, std::function<void(const std::string&)> on_step)
    : s_(s),
      robust_(with_robust_cfd(s)),
      isotropic_(with_isotropic_band(s)),
      isotropic_robust_(with_robust_cfd(isotropic_)),
      cache_(out_dir),
      np_(np),
      force_(std::move(force)),
      on_step_(std::move(on_step)) {}

const scene::Scene& GridRunner::scene_for(const GridVariant& v) const {
  if (v.isotropic) return v.robust ? isotropic_robust_ : isotropic_;
  return v.robust ? robust_ : s_;
}

std::string GridRunner::robust_scheme() const {
  return scheme_name(robust_.cfd.flux_scheme, robust_.cfd.limiter);
}

bool GridRunner::forced(const std::string& stage) const { return force_.count(stage) != 0 || force_.count("all") != 0; }

std::string GridRunner::case_dir(const std::string& family, double level) const {
  return cache_.dir("cfd/" + level_name(family, level));
}
std::string GridRunner::mesh_dir(const std::string& family, double level) const {
  return cache_.dir("meshgen/" + level_name(family, level));
}

// Meshed and cached; meshgen's summary gains the stage's CPU seconds (meshgen
// in-process, gmsh, checkMesh and gnuplot as children).
nlohmann::json GridRunner::mesh(const std::string& family, double level, const ShockInput& shock,
                                const GridVariant& v) {
  const scene::Scene& ms = scene_for(v);
  const bool clustered = is_clustered(family);
  const std::string stage = "meshgen/" + level_name(family, level) + v.mesh_suffix();
  const std::string fp =
      fingerprint({clustered ? shock.fingerprint : "", scene::section_yaml(ms, "body"),
                   scene::section_yaml(ms, "domain"), scene::section_yaml(ms, "mesh"),
                   clustered ? "clustered" : "uniform", std::to_string(level)});
  if (forced("meshgen")) cache_.invalidate(stage);
  if (cache_.fresh(stage, fp)) return cache_.result(stage);
  cache_.invalidate(stage);
  meshgen::MeshRequest req = clustered ? clustered_request(shock, level) : meshgen::MeshRequest{};
  req.uniform = !clustered;
  req.h_min = ms.mesh.h_min * level;
  req.h_max = clustered ? ms.mesh.h_max * level : ms.mesh.h_min * level;
  // An explicit body size is refined with the other sizes of the ladder.
  if (clustered && ms.mesh.h_body) req.h_body = *ms.mesh.h_body * level;
  const scene::CpuStopwatch cpu;
  const auto m = meshgen::generate_mesh(ms, req, cache_.dir(stage));
  nlohmann::json msum = m.summary();
  msum["seconds"] = m.seconds;
  msum["stage_cpu_seconds"] = cpu.seconds();
  msum["fingerprint"] = fp;
  cache_.mark_done(stage, fp, msum);
  return msum;
}

// rhoCentralFoam to a measured steady state, cached; the summary gains the
// solver's CPU seconds (all ranks, as waited-for children).
nlohmann::json GridRunner::solve(const std::string& mesh_name, const std::string& case_name,
                                 const scene::Scene& cs, const std::string& fp_mesh) {
  const std::string mstage = "meshgen/" + mesh_name, cstage = "cfd/" + case_name;
  const std::string fp =
      fingerprint({fp_mesh, scene::section_yaml(cs, "cfd"), scene::section_yaml(cs, "freestream")});
  if (forced("cfd")) cache_.invalidate(cstage);
  if (cache_.fresh(cstage, fp)) return cache_.result(cstage);
  cache_.invalidate(cstage);
  cfd::CaseOptions co;
  co.np = np_;
  const scene::CpuStopwatch cpu;
  const auto c = cfd::run_case_with_fallback(cs, cache_.dir(mstage), cache_.dir(cstage), co);
  const double solver_cpu = cpu.seconds();
  check_interrupt("cfd " + case_name);
  const auto lat = cfd::resample_to_lattice(s_, cache_.dir(cstage), s_.granular.lattice_nx, s_.granular.lattice_ny);
  scene::write_vti(lat, cache_.dir(cstage) + "/fields.vti");
  nlohmann::json csum = c.summary();
  csum["stage_cpu_seconds"] = solver_cpu;
  csum["fingerprint"] = fp;
  cache_.mark_done(cstage, fp, csum);
  return csum;
}

// The CFD shock, located like the granular one with the shock window
// widened to the grid's smeared shock (same rule for every family).
nlohmann::json GridRunner::locate(const std::string& case_name, double level,
                                  const std::string& fp_cfd) {
  const std::string cstage = "cfd/" + case_name, fstage = cstage + "/shockfit";
  const scene::Scene fs_scene = cfd_shockfit_scene(s_, level * s_.mesh.h_min);
  const std::string fp = fingerprint({fp_cfd, scene::section_yaml(fs_scene, "shockfit")});
  if (!forced("cfd") && cache_.fresh(fstage, fp)) return cache_.result(fstage);
  cache_.invalidate(fstage);
  const auto lat = scene::read_vti(cache_.dir(cstage) + "/fields.vti");
  const auto sh = shockfit::locate_shock(fs_scene, lat);
  shockfit::write_outputs(fs_scene, lat, sh, cache_.dir(fstage));
  nlohmann::json fsum = sh.summary();
  fsum["shock_value"] = shock_value(sh);
  fsum["shock_value_ci"] = shock_ci(sh);
  cache_.mark_done(fstage, fp, fsum);
  return fsum;
}

// A shock of the other kind than the flow's (shockfit reading the Mach 2,
// 30 deg wedge's near-normal bow shock as an attached line at 72 deg, whose
// angle then stood in the standoff column) measures nothing comparable: no
// value, and a note in the report.
std::optional<std::string> foreign_shock_note(const scene::Scene& s, const std::string& shock_kind) {
  const scene::ShockKind expected =
      scene::attached_shock_beta(s) ? scene::ShockKind::attached : scene::ShockKind::detached;
  const scene::ShockKind found = scene::shock_kind_from(shock_kind);
  if (found == expected || found == scene::ShockKind::none) return std::nullopt;
  return "shockfit found an " + shock_kind + " shock on a " + scene::to_string(expected) +
         "-shock flow: no shock value";
}

void GridRunner::drop_foreign_shock(GridRun& run) const {
  const auto note = foreign_shock_note(s_, run.shock);
  if (!note) return;
  run.note += (run.note.empty() ? "" : "; ") + *note;
  run.value = run.value_ci = kNaN;
}

// A failure to measure is not silent: it becomes the run's note, shown in the report.
void GridRunner::measure(const std::string& case_name, const PrimaryError& primary,
                         GridRun& run) const {
  try {
    const CaseErrors e = measure_case_errors(s_, cache_.dir("cfd/" + case_name));
    run.l1_density = e.l1_density.value;
    run.l1_density_ci = e.l1_density.uncertainty;
    run.l1_pressure = e.l1_pressure.value;
    run.stagnation_pressure_ratio = e.stagnation_pressure_ratio;
    run.stagnation_pressure_error = e.stagnation_pressure.value;
    run.drag_coefficient = e.drag_coefficient;
    run.l1_total_enthalpy = e.l1_total_enthalpy.value;
    run.stagnation_pressure_error_ci = e.stagnation_pressure.uncertainty;
    run.shock_axis_deviation_cells = e.shock_axis_deviation_cells;
    const MeasuredError p = measure_named(e, primary.name);
    run.primary_error = p.value;
    run.primary_error_ci = std::isfinite(p.uncertainty) ? p.uncertainty : 0.0;
  } catch (const std::exception& ex) {
    run.note = std::string("error measures failed: ") + ex.what();
    scene::log_line("pipeline: " + case_name + ": " + run.note, true);
  }
}

GridRun GridRunner::run(const std::string& family, double level, const ShockInput& shock,
                        const PrimaryError& primary, GridVariant variant) {
  const std::string name = level_name(family, level);
  const std::string mesh_name = name + variant.mesh_suffix();
  const nlohmann::json msum = mesh(family, level, shock, variant);
  check_interrupt("meshgen " + mesh_name);
  if (on_step_) on_step_("mesh " + mesh_name);
  GridRun run;
  run.family = family;
  run.level = level;
  run.cells = msum.value("cells", 0L);
  run.mesh_seconds = msum.value("seconds", 0.0);
  run.mesh_cpu_seconds = number_or_nan(msum, "stage_cpu_seconds");
  run.mesh_name = mesh_name;
  run.strips = msum.value("band_strips", 0L) > 0;
  if (!s_.pipeline.cfd) return run;
  const std::string case_name = name + variant.case_suffix();
  const nlohmann::json csum =
      solve(mesh_name, case_name, scene_for(variant), msum.value("fingerprint", ""));
  const nlohmann::json fsum = locate(case_name, level, csum.value("fingerprint", ""));
  run.cfd_wall_seconds = number_or_nan(csum, "wall_seconds");
  run.cfd_cpu_seconds = number_or_nan(csum, "stage_cpu_seconds");
  run.steps = csum.value("steps", 0L);
  run.flow_throughs = number_or_nan(csum, "flow_throughs");
  run.steady = csum.value("steady_state_reached", false);
  run.scheme = case_scheme(csum);
  run.case_name = case_name;
  if (csum.contains("fallback") && csum["fallback"].is_string()) {
    run.fell_back = true;
    run.note = "diverged; restarted with " + csum["fallback"].get<std::string>();
  }
  run.shock = fsum.value("shock", "none");
  run.value = number_or_nan(fsum, "shock_value");
  run.value_ci = number_or_nan(fsum, "shock_value_ci");
  drop_foreign_shock(run);
  run.wall_pressure_ratio = number_or_nan(csum, "wall_pressure_ratio");
  measure(case_name, primary, run);
  if (on_step_) on_step_("cfd " + case_name);
  return run;
}

}  // namespace pipeline
