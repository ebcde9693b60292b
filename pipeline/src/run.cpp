#include "pipeline/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include "cfd/run_case.hpp"
#include "granular/flow_run.hpp"
#include "meshgen/mesh.hpp"
#include "pipeline/calibration.hpp"
#include "pipeline/compare.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/grid_convergence.hpp"
#include "pipeline/report.hpp"
#include "pipeline/stage_cache.hpp"
#include "pipeline/verdict.hpp"
#include "scene/body.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/progress.hpp"
#include "shockfit/locate.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = std::numbers::pi / 180.0;
// Digits kept of a calibrated restitution: the resolved scene echoes it
// exactly, so rerunning the resolved scene reproduces the run bit for bit.
constexpr double kRestitutionQuantum = 1e-6;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void check_interrupt(const std::string& where) {
  if (scene::interrupted())
    throw scene::RunError("interrupted during " + where + "; finished stages are kept, rerun to resume");
}

bool forced(const RunOptions& o, const std::string& stage) {
  return o.force.count(stage) != 0 || o.force.count("all") != 0;
}

std::string level_name(const std::string& family, double level) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_h%g", family.c_str(), level);
  return buf;
}

double number_or_nan(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

Reference reference_for(const scene::Scene& s) {
  Reference r;
  r.pressure_ratio = kNaN;
  const auto& b = *s.body;
  if (b.kind == scene::BodyKind::wedge) {
    const auto beta = scene::oblique_shock_beta(s.freestream.mach, b.angle_deg * kDeg, s.freestream.gamma);
    if (beta) {
      r.quantity = "shock_angle_deg";
      r.source = "theta-beta-Mach relation";
      r.value = *beta / kDeg;
      r.pressure_ratio = scene::oblique_pressure_ratio(s.freestream.mach, *beta, s.freestream.gamma);
      return r;
    }
  }
  r.quantity = "standoff";
  if (b.kind == scene::BodyKind::disc) {
    r.source = "Billig's correlation for cylinders (a comparison, not an exact reference)";
    r.value = scene::billig_standoff_cylinder(s.freestream.mach);  // in radii = body lengths
  } else {
    r.source = "finest uniform grid (a comparison, not an exact reference)";
    r.value = kNaN;  // filled from the finest uniform run
  }
  return r;
}

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
  if (r.shock == "attached") return r.shock_angle_deg;
  if (r.shock == "detached") return r.standoff;
  return kNaN;
}
double shock_ci(const shockfit::ShockResult& r) {
  if (r.shock == "attached") return r.shock_angle_ci_deg;
  if (r.shock == "detached") return r.standoff_ci;
  return kNaN;
}

// What the grids need of the prediction.
struct PredictionInfo {
  std::string fingerprint;  // of the shockfit stage: clustered grids depend on it
  std::string shock_csv;
  bool has_shock = false;
};

// What one pipeline run shares between its steps.
struct Context {
  const scene::Scene& s;
  const RunOptions& o;
  StageCache cache;
  scene::Progress& progress;
  int done = 0;
  void step(const std::string& what) { progress.update(++done, what); }
};

// A grid of either family, meshed and cached; returns meshgen's summary with
// the stage's CPU seconds (gmsh in-process, gmshToFoam and checkMesh as children).
nlohmann::json mesh_grid(Context& cx, const std::string& family, double level, const std::string& fp_shock,
                         const std::string& shock_csv) {
  const auto& s = cx.s;
  const bool clustered = family == "clustered";
  const std::string stage = "meshgen/" + level_name(family, level);
  const std::string fp = fingerprint({clustered ? fp_shock : "", scene::section_yaml(s, "body"),
                                      scene::section_yaml(s, "domain"), scene::section_yaml(s, "mesh"), family,
                                      std::to_string(level)});
  if (forced(cx.o, "meshgen")) cx.cache.invalidate(stage);
  if (cx.cache.fresh(stage, fp)) return cx.cache.result(stage);
  cx.cache.invalidate(stage);
  meshgen::MeshRequest req = clustered ? meshgen::request_from_shock_csv(shock_csv) : meshgen::MeshRequest{};
  req.uniform = !clustered;
  req.h_min = s.mesh.h_min * level;
  req.h_max = clustered ? s.mesh.h_max * level : s.mesh.h_min * level;
  const scene::CpuStopwatch cpu;
  const auto m = meshgen::generate_mesh(s, req, cx.cache.dir(stage));
  nlohmann::json msum = m.summary();
  msum["seconds"] = m.seconds;
  msum["stage_cpu_seconds"] = cpu.seconds();
  msum["fingerprint"] = fp;
  cx.cache.mark_done(stage, fp, msum);
  return msum;
}

// rhoCentralFoam on a meshed grid to a measured steady state, cached; the
// summary gains the solver's CPU seconds (all ranks, as waited-for children).
nlohmann::json solve_grid(Context& cx, const std::string& name, const std::string& fp_mesh) {
  const auto& s = cx.s;
  const std::string mstage = "meshgen/" + name, cstage = "cfd/" + name;
  const std::string fp = fingerprint({fp_mesh, scene::section_yaml(s, "cfd"), scene::section_yaml(s, "freestream")});
  if (forced(cx.o, "cfd")) cx.cache.invalidate(cstage);
  if (cx.cache.fresh(cstage, fp)) return cx.cache.result(cstage);
  cx.cache.invalidate(cstage);
  cfd::CaseOptions co;
  co.np = cx.o.np;
  const scene::CpuStopwatch cpu;
  const auto c = cfd::run_case(s, cx.cache.dir(mstage), cx.cache.dir(cstage), co);
  const double solver_cpu = cpu.seconds();
  check_interrupt("cfd " + name);
  const auto lat = cfd::resample_to_lattice(s, cx.cache.dir(cstage), s.granular.lattice_nx, s.granular.lattice_ny);
  scene::write_vti(lat, cx.cache.dir(cstage) + "/fields.vti");
  nlohmann::json csum = c.summary();
  csum["stage_cpu_seconds"] = solver_cpu;
  csum["fingerprint"] = fp;
  cx.cache.mark_done(cstage, fp, csum);
  return csum;
}

// The CFD shock, located like the granular one with the shock window
// widened to the grid's smeared shock (same rule for both families).
nlohmann::json locate_cfd_shock(Context& cx, const std::string& name, double level, const std::string& fp_cfd) {
  const std::string cstage = "cfd/" + name, fstage = cstage + "/shockfit";
  const scene::Scene fs_scene = cfd_shockfit_scene(cx.s, level * cx.s.mesh.h_min);
  const std::string fp = fingerprint({fp_cfd, scene::section_yaml(fs_scene, "shockfit")});
  if (!forced(cx.o, "cfd") && cx.cache.fresh(fstage, fp)) return cx.cache.result(fstage);
  cx.cache.invalidate(fstage);
  const auto lat = scene::read_vti(cx.cache.dir(cstage) + "/fields.vti");
  const auto sh = shockfit::locate_shock(fs_scene, lat);
  shockfit::write_outputs(fs_scene, lat, sh, cx.cache.dir(fstage));
  nlohmann::json fsum = sh.summary();
  fsum["shock_value"] = shock_value(sh);
  fsum["shock_value_ci"] = shock_ci(sh);
  cx.cache.mark_done(fstage, fp, fsum);
  return fsum;
}

// The exact-reference error measures of a finished case. A failure to
// measure is not silent: it is kept as the run's note and shown in the report.
void measure_errors(Context& cx, const std::string& name, const PrimaryError& primary, GridRun& run) {
  try {
    const CaseErrors e = measure_case_errors(cx.s, cx.cache.dir("cfd/" + name));
    run.l1_density = e.l1_density.value;
    run.l1_density_ci = e.l1_density.uncertainty;
    run.l1_pressure = e.l1_pressure.value;
    run.stagnation_pressure_ratio = e.stagnation_pressure_ratio;
    run.stagnation_pressure_error = e.stagnation_pressure.value;
    run.drag_coefficient = e.drag_coefficient;
    const MeasuredError& p = primary.name == "l1_density" ? e.l1_density : e.stagnation_pressure;
    run.primary_error = p.value;
    run.primary_error_ci = std::isfinite(p.uncertainty) ? p.uncertainty : 0.0;
  } catch (const std::exception& ex) {
    run.note = std::string("error measures failed: ") + ex.what();
    scene::log_line("pipeline: " + name + ": " + run.note, true);
  }
}

// One member of a family: mesh, solve, locate the CFD shock, measure.
GridRun run_member(Context& cx, const std::string& family, double level, const PredictionInfo& pred,
                   const PrimaryError& primary) {
  const std::string name = level_name(family, level);
  const nlohmann::json msum = mesh_grid(cx, family, level, pred.fingerprint, pred.shock_csv);
  check_interrupt("meshgen " + name);
  cx.step("mesh " + name);
  GridRun run;
  run.family = family;
  run.level = level;
  run.cells = msum.value("cells", 0L);
  run.mesh_seconds = msum.value("seconds", 0.0);
  run.mesh_cpu_seconds = number_or_nan(msum, "stage_cpu_seconds");
  if (!cx.s.pipeline.cfd) return run;
  const nlohmann::json csum = solve_grid(cx, name, msum.value("fingerprint", ""));
  const nlohmann::json fsum = locate_cfd_shock(cx, name, level, csum.value("fingerprint", ""));
  run.cfd_wall_seconds = number_or_nan(csum, "wall_seconds");
  run.cfd_cpu_seconds = number_or_nan(csum, "stage_cpu_seconds");
  run.steps = csum.value("steps", 0L);
  run.flow_throughs = number_or_nan(csum, "flow_throughs");
  run.steady = csum.value("steady_state_reached", false);
  run.shock = fsum.value("shock", "none");
  run.value = number_or_nan(fsum, "shock_value");
  run.value_ci = number_or_nan(fsum, "shock_value_ci");
  run.wall_pressure_ratio = number_or_nan(csum, "wall_pressure_ratio");
  measure_errors(cx, name, primary, run);
  cx.step("cfd " + name);
  return run;
}

// Levels are user numbers (2.8, 1.4): equal within this relative slack.
constexpr double kLevelSlack = 1e-9;

const GridRun* at_level(const std::vector<GridRun>& fam, double level) {
  for (const auto& r : fam)
    if (std::abs(r.level - level) <= kLevelSlack * level) return &r;
  return nullptr;
}

nlohmann::json convergence_json(const GridConvergence& g) {
  auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"monotone", g.monotone}, {"observed_order", num(g.order)}, {"extrapolated", num(g.extrapolated)},
          {"gci_fine", num(g.gci_fine)}, {"note", g.note}};
}

// Bodies without an exact field solution: one uniform grid finer than every
// family member (in neither family), and Richardson extrapolation of the
// standoff and the drag coefficient from it and the uniform grids two and
// four times coarser. Null when the scene needs none or it cannot be formed.
nlohmann::json reference_study(Context& cx, const PredictionInfo& info, const PrimaryError& primary,
                               const std::vector<GridRun>& uniform) {
  const auto& p = cx.s.pipeline;
  if (primary.name == "l1_density" || !p.reference_grid || !p.cfd || p.levels.empty()) return nullptr;
  const double finest = *std::min_element(p.levels.begin(), p.levels.end());
  const double level = p.reference_level.value_or(0.5 * finest);
  constexpr double kRatio = 2.0;
  const GridRun* r2 = at_level(uniform, level * kRatio);
  const GridRun* r3 = at_level(uniform, level * kRatio * kRatio);
  const GridRun ref = run_member(cx, "reference", level, info, primary);
  nlohmann::json j;
  j["reference_run"] = ref.to_json();
  j["refinement_ratio"] = kRatio;
  if (!r2 || !r3) {
    j["note"] = "no uniform grids at 2x and 4x the reference level: no Richardson triple";
    return j;
  }
  j["triple"] = {ref.level, r2->level, r3->level};
  j["standoff"] = convergence_json(richardson(ref.value, r2->value, r3->value, kRatio));
  j["drag_coefficient"] =
      convergence_json(richardson(ref.drag_coefficient, r2->drag_coefficient, r3->drag_coefficient, kRatio));
  j["stagnation_pressure_ratio"] = convergence_json(
      richardson(ref.stagnation_pressure_ratio, r2->stagnation_pressure_ratio, r3->stagnation_pressure_ratio, kRatio));
  return j;
}

std::vector<VerdictRun> verdict_runs(const std::vector<GridRun>& runs) {
  std::vector<VerdictRun> out;
  for (const auto& r : runs)
    out.push_back({r.family, r.level, r.cells, r.cfd_cpu_seconds, r.mesh_cpu_seconds, r.primary_error,
                   r.primary_error_ci, r.steady});
  return out;
}

}  // namespace

std::string builtin_calibration_path() { return std::string(PIPELINE_SOURCE_DIR) + "/calibration.yaml"; }

std::string apply_calibration(scene::Scene& s, const std::string& table_path) {
  if (!s.body || s.granular.restitution_given) return "";
  // Wedges interpolate in (Mach, angle). Other bodies have no wedge angle:
  // they take the table's e at their Mach number, an extrapolation from
  // wedges that the report states (a disc at Mach 4: standoff 1.76 radii at
  // e = 1, 0.60 at the table's e = 0.975, against Billig's 0.52).
  const bool wedge = s.body->kind == scene::BodyKind::wedge;
  std::string path = table_path;
  if (path.empty()) path = s.pipeline.calibration.empty() ? builtin_calibration_path() : s.pipeline.calibration;
  if (!fs::exists(path)) return "no calibration table at " + path + "; restitution left at its default";
  const auto t = read_calibration(path);
  const auto e = interpolate_restitution(t, s.freestream.mach, wedge ? s.body->angle_deg : kNaN);
  if (!e) return "";
  s.granular.restitution = std::round(*e / kRestitutionQuantum) * kRestitutionQuantum;
  char buf[400];
  std::snprintf(buf, sizeof buf, "granular.restitution = %.6f from the calibration table %s%s",
                s.granular.restitution, path.c_str(),
                wedge ? "" : " (by Mach number alone: the table is calibrated on wedges, so this is an extrapolation)");
  return buf;
}

nlohmann::json run_prediction(const scene::Scene& s, const std::string& out_dir, int np, bool force) {
  StageCache cache(out_dir);
  const std::string fp_g = fingerprint({scene::section_yaml(s, "body"), scene::section_yaml(s, "freestream"),
                                        scene::section_yaml(s, "domain"), scene::section_yaml(s, "granular")});
  nlohmann::json gsum;
  scene::Lattice fields;
  if (!force && cache.fresh("granular", fp_g)) {
    gsum = cache.result("granular");
    fields = scene::read_vti(cache.dir("granular") + "/fields.vti");
  } else {
    cache.invalidate("granular");
    granular::RunOptions go;
    go.out_dir = cache.dir("granular");
    go.np = np;
    const scene::CpuStopwatch cpu;
    auto r = granular::run_flow_scene(s, go);
    check_interrupt("the granular stage");
    if (r.summary.value("interrupted", false))
      throw scene::RunError("interrupted during the granular stage; rerun to resume");
    gsum = r.summary;
    gsum["stage_cpu_seconds"] = cpu.seconds();
    fields = std::move(r.fields);
    cache.mark_done("granular", fp_g, gsum);
  }
  const std::string fp_s = fingerprint({fp_g, scene::section_yaml(s, "shockfit")});
  nlohmann::json ssum;
  if (!force && cache.fresh("shockfit", fp_s)) {
    ssum = cache.result("shockfit");
  } else {
    cache.invalidate("shockfit");
    const scene::CpuStopwatch cpu;
    const auto r = shockfit::locate_shock(s, fields);
    shockfit::write_outputs(s, fields, r, cache.dir("shockfit"));
    ssum = r.summary();
    ssum["stage_cpu_seconds"] = cpu.seconds();
    cache.mark_done("shockfit", fp_s, ssum);
  }
  nlohmann::json out = ssum;
  out["granular_wall_seconds"] = gsum.value("wall_seconds", kNaN);
  out["granular_cpu_seconds"] = number_or_nan(gsum, "stage_cpu_seconds");
  out["shockfit_cpu_seconds"] = number_or_nan(ssum, "stage_cpu_seconds");
  out["predictor_cpu_seconds"] = number_or_nan(gsum, "stage_cpu_seconds") + number_or_nan(ssum, "stage_cpu_seconds");
  out["granular"] = gsum;
  out["fingerprint"] = fp_s;
  return out;
}

nlohmann::json run_pipeline(scene::Scene s, const RunOptions& o) {
  if (!s.body) throw scene::InputError(s.source_file + ": the pipeline needs a body scene");
  const auto t_start = std::chrono::steady_clock::now();
  scene::make_dirs(o.out_dir);
  const std::string calib_note = apply_calibration(s, o.calibration_path);
  if (!calib_note.empty()) scene::log_line("pipeline: " + calib_note);
  scene::write_file_atomic(o.out_dir + "/scene.resolved.yaml", scene::to_yaml(s));
  const auto& levels = s.pipeline.levels;
  const int n_stages = 2 + (s.pipeline.cfd ? 2 : 1) * (2 * static_cast<int>(levels.size()) + 1) + 1;
  scene::Progress progress("pipeline", n_stages, "stages");
  Context cx{s, o, StageCache(o.out_dir), progress};

  // The prediction: granular gas and its fitted shock.
  if (forced(o, "granular")) cx.cache.invalidate("granular");
  if (forced(o, "shockfit")) cx.cache.invalidate("shockfit");
  const auto pred = run_prediction(s, o.out_dir, o.np);
  check_interrupt("shockfit");
  cx.done = 2;
  cx.step("granular + shockfit");
  const PredictionInfo info{pred.value("fingerprint", ""), cx.cache.dir("shockfit") + "/shock.csv",
                            pred.value("shock", "none") != "none"};

  // Both families, coarse to fine.
  const PrimaryError primary = primary_error_for(s);
  std::vector<GridRun> fam_c, fam_u;
  for (const double level : levels) fam_u.push_back(run_member(cx, "uniform", level, info, primary));
  if (info.has_shock) {
    for (const double level : levels) fam_c.push_back(run_member(cx, "clustered", level, info, primary));
  } else {
    scene::log_line("pipeline: no granular shock found; no clustered grids", true);
  }

  const nlohmann::json convergence = reference_study(cx, info, primary, fam_u);

  // Comparison, verdict and report.
  Reference ref = reference_for(s);
  if (!std::isfinite(ref.value) && !fam_u.empty()) ref.value = fam_u.back().value;
  for (auto& r : fam_c) score(r, ref);
  for (auto& r : fam_u) score(r, ref);
  const Comparison cmp = compare(fam_c, fam_u, pred.value("granular_wall_seconds", 0.0));
  const Verdict verdict =
      make_verdict(primary, verdict_runs(fam_c), verdict_runs(fam_u), number_or_nan(pred, "predictor_cpu_seconds"));
  ReportInputs in{s, o.out_dir, pred, ref, cmp, verdict, calib_note, seconds_since(t_start), convergence};
  const nlohmann::json summary = make_summary(in);
  scene::write_json_atomic(o.out_dir + "/summary.json", summary);
  write_report(in, summary);
  cx.step("report");
  progress.finish();
  return summary;
}

}  // namespace pipeline
