#include "pipeline/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "granular/flow_run.hpp"
#include "json_fields.hpp"
#include "pipeline/calibration.hpp"
#include "pipeline/compare.hpp"
#include "pipeline/grid_convergence.hpp"
#include "pipeline/grid_runs.hpp"
#include "pipeline/one_scheme.hpp"
#include "pipeline/precision_goal.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/report.hpp"
#include "pipeline/stage_cache.hpp"
#include "pipeline/strip_fallback.hpp"
#include "pipeline/studies.hpp"
#include "pipeline/verdict.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/dir_lock.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/group_fields.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/progress.hpp"
#include "scene/units.hpp"
#include "shockfit/group_interval.hpp"
#include "shockfit/locate.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {

using scene::kDeg;
using scene::kNaN;
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Reference reference_for(const scene::Scene& s) {
  Reference r;
  r.pressure_ratio = kNaN;
  if (const auto beta = scene::attached_shock_beta(s)) {
    r.quantity = "shock_angle_deg";
    r.source = "theta-beta-Mach relation";
    r.value = *beta / kDeg;
    r.pressure_ratio = scene::oblique_pressure_ratio(s.freestream.mach, *beta, s.freestream.gamma);
    return r;
  }
  r.quantity = "standoff";
  if (scene::correlation_is_exact_shape(*s.body)) {
    r.source = "Billig's correlation for cylinders (a comparison, not an exact reference)";
    r.value = scene::billig_standoff_cylinder(s.freestream.mach) *
              scene::correlation_nose_radius(*s.body) / scene::body_length(*s.body);
  } else {
    r.source = "finest uniform grid (a comparison, not an exact reference)";
    r.value = kNaN;  // filled from the finest uniform run
  }
  return r;
}

const GridRun* at_level(const std::vector<GridRun>& fam, double level) {
  for (const auto& r : fam)
    if (same_level(r.level, level)) return &r;
  return nullptr;
}

nlohmann::json convergence_json(const GridConvergence& g) {
  return {{"monotone", g.monotone},
          {"observed_order", json_number(g.order)},
          {"extrapolated", json_number(g.extrapolated)},
          {"gci_fine", json_number(g.gci_fine)},
          {"note", g.note}};
}

// Bodies without an exact field solution: one uniform grid finer than every
// family member (in neither family), and Richardson extrapolation of the
// standoff, drag and stagnation pressure from it and the uniform grids two
// and four times coarser (grid_runs.hpp: reference_grid_level). Null when
// the scene needs none.
nlohmann::json reference_study(const scene::Scene& s, GridRunner& grids,
                               const PrimaryError& primary, const std::vector<GridRun>& uniform,
                               bool robust) {
  const auto& p = s.pipeline;
  if (primary.name == "l1_density" || !p.reference_grid || !p.cfd || p.levels.empty())
    return nullptr;
  const double level = reference_grid_level(p);
  constexpr double kRatio = 2.0;
  const GridRun* r2 = at_level(uniform, level * kRatio);
  const GridRun* r3 = at_level(uniform, level * kRatio * kRatio);
  GridVariant variant;
  variant.robust = robust;
  const GridRun ref = grids.run("reference", level, {}, primary, variant);
  nlohmann::json j;
  j["reference_run"] = ref.to_json();
  j["refinement_ratio"] = kRatio;
  if (!r2 || !r3) {
    j["note"] = "no uniform grids at 2x and 4x the reference level: no Richardson triple";
    return j;
  }
  if (ref.scheme != r2->scheme || ref.scheme != r3->scheme)
    j["scheme_note"] = "the triple mixes schemes (" + ref.scheme + " on the reference grid, " +
                       r2->scheme + " and " + r3->scheme +
                       " below it): its estimates mix their truncation errors";
  j["triple"] = {ref.level, r2->level, r3->level};
  j["standoff"] = convergence_json(richardson(ref.value, r2->value, r3->value, kRatio));
  j["drag_coefficient"] = convergence_json(
      richardson(ref.drag_coefficient, r2->drag_coefficient, r3->drag_coefficient, kRatio));
  j["stagnation_pressure_ratio"] =
      convergence_json(richardson(ref.stagnation_pressure_ratio, r2->stagnation_pressure_ratio,
                                  r3->stagnation_pressure_ratio, kRatio));
  return j;
}

// The table a scene's run reads: --calibration, else the scene's
// pipeline.calibration, else the one built in.
std::string calibration_path(const scene::Scene& s, const std::string& table_path) {
  if (!table_path.empty()) return table_path;
  return s.pipeline.calibration.empty() ? builtin_calibration_path() : s.pipeline.calibration;
}

std::vector<VerdictRun> verdict_runs(const std::vector<GridRun>& runs) {
  std::vector<VerdictRun> out;
  for (const auto& r : runs)
    out.push_back({r.family, r.level, r.cells, r.steps, r.cfd_cpu_seconds, r.mesh_cpu_seconds,
                   r.primary_error, r.primary_error_ci, r.steady, r.case_name});
  return out;
}

// The granular predictor keeps its stages at the run's top level (granular/,
// shockfit/), as it always has; the others get predict/<name>/.
std::string predictor_dir(const std::string& out_dir, const std::string& name) {
  return name == "granular" ? out_dir : out_dir + "/predict/" + name;
}

}  // namespace

// Clustered grids of the default predictor keep their historic names.
std::string clustered_family(const std::string& predictor) {
  return predictor == "granular" ? "clustered" : "clustered-" + predictor;
}

std::string builtin_calibration_path() {
  return std::string(PIPELINE_SOURCE_DIR) + "/calibration.yaml";
}

namespace {
constexpr const char* kUnmeasuredError =
    "this prediction's error is unmeasured (its band may miss the gas shock)";

std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "; WARNING: <subject> lies outside <range_name> <low>-<high><unit>, so <consequence>": one
// form for every range a calibration was measured over.
std::string outside_warning(const std::string& subject, const char* range_name, MachRange r,
                            const char* unit, const std::string& consequence) {
  return "; WARNING: " + subject + " lies outside " + range_name + " " + shortest(r.low) + "-" +
         shortest(r.high) + unit + ", so " + consequence;
}
// What the band takes where the table measured its extrapolation's error.
std::string extrapolation_measured(const AngleScatter& b, double mach,
                                   const std::string& whose = "the extrapolation's own") {
  char deg[32];
  std::snprintf(deg, sizeof deg, "%.3f", b.deg);
  std::string out = "the band takes " + whose + " angle error, " + deg + " deg, measured on " +
                    std::to_string(b.wedges) + " unseen wedges at Mach " + shortest(b.mach_low) +
                    "-" + shortest(b.mach_high);
  if (!MachRange{b.mach_low, b.mach_high}.contains(mach))
    out += ", not at this Mach number: " + std::string(kUnmeasuredError);
  return out;
}
// The deflection a wedge fit can match: a wedge's whose gas shock is attached.
std::optional<double> attached_wedge_angle_deg(const scene::Scene& s) {
  if (scene::shock_may_stand_off(s)) return std::nullopt;
  return scene::calibration_angle_deg(*s.body);
}
}  // namespace

void require_named_calibration(const scene::Scene& s, const std::string& table_path) {
  if (!table_path.empty() && !fs::is_regular_file(table_path))
    throw scene::InputError(table_path +
                            ": --calibration file not found (a restitution table from "
                            "`pipeline calibrate`)");
  if (table_path.empty() && !s.pipeline.calibration.empty() &&
      !fs::is_regular_file(s.pipeline.calibration))
    throw scene::InputError((s.source_file.empty() ? "scene " + s.name : s.source_file) +
                            ": key 'pipeline.calibration': file " + s.pipeline.calibration +
                            " not found");
}

AppliedCalibration apply_calibration(scene::Scene& s, const std::string& table_path) {
  if (!s.body || s.granular.restitution_given) return {};
  require_named_calibration(s, table_path);
  if (s.granular.elastic_impact_speed > 0.0)
    throw scene::InputError(
        (s.source_file.empty() ? "scene " + s.name : s.source_file) +
        ": key 'granular.elastic_impact_speed': the calibration tables are fitted without "
        "elastic slow impacts, so no table gives this gas's restitution; set "
        "granular.restitution as well");
  // Wedges interpolate in (Mach, angle). Other bodies have no wedge angle:
  // they take the table's e at their Mach number, an extrapolation from
  // wedges that the report states. The wedge fit matches attached shock
  // angles: a wedge beyond the gas's maximum deflection has none to match,
  // its shock stands off as a blunt body's does, so it is calibrated as one
  // (the fit's theta^2 term, extrapolated to 30-45 deg, would push it towards
  // the elastic limit).
  const std::optional<double> wedge_deg = scene::calibration_angle_deg(*s.body);
  const std::optional<double> angle_deg = attached_wedge_angle_deg(s);
  const bool detached_wedge = wedge_deg && !angle_deg;
  const std::string path = calibration_path(s, table_path);
  if (!fs::exists(path))
    return {"no calibration table at " + path + "; restitution left at its default"};
  const auto t = read_calibration(path);
  // A blunt shape with its own fit takes it: the wedge e(M) misplaces bow shocks.
  const auto shape_name = wedge_deg ? std::nullopt : scene::bow_shape_class(*s.body);
  const BowShapeFit* shape = shape_name && t.bow_shock ? t.bow_shock->shape(*shape_name) : nullptr;
  const auto e = shape ? std::optional<double>(shape->evaluate(s.freestream.mach))
                       : interpolate_restitution(t, s.freestream.mach, angle_deg.value_or(kNaN));
  if (!e) return {"", t.cpu_seconds};
  s.granular.restitution = quantised_restitution(*e);
  // The wedge table's angle scatter says nothing about a bow shock's standoff;
  // the table's bow-shock block, measured on blunt bodies, does. Every body
  // gets it and the predictor uses it on a shock it finds detached: blunt
  // bodies, a wedge beyond its maximum deflection, and a wedge just below it,
  // where the granular gas's shock detaches first.
  const double scatter = wedge_deg ? table_angle_scatter_deg(t, s.freestream.mach) : kNaN;
  // A shape that runs at the law may have its fold measured: its stations are
  // corrected and its band takes the corrected stations' left-out scatter.
  const BowStationBias* bias =
      shape_name && !shape && t.bow_shock ? t.bow_shock->station_bias(*shape_name) : nullptr;
  const double bow = shape         ? shape->relative_rms
                     : bias        ? bias->relative_rms
                     : t.bow_shock ? t.bow_shock->relative_rms
                                   : kNaN;
  // Where the restitution came from; a long table path is kept whole.
  const std::string source =
      shape ? " (its own fit for the " + shape->shape + " shape, trained on " +
                  std::to_string(shape->points.size()) + " bow shocks)"
      : detached_wedge
          ? " (by Mach number alone, the blunt bodies' law: the wedge is beyond the gas's "
            "maximum deflection, so its shock stands off and no attached angle calibrates it)"
      : angle_deg ? (t.local_correction ? " (its model with the local correction at this Mach "
                                          "number and deflection)"
                                        : "")
                  : " (by Mach number alone: the table is calibrated on wedges, so this is an "
                    "extrapolation)";
  char value[32];
  std::snprintf(value, sizeof value, "%.6f", s.granular.restitution);
  std::string note = std::string("granular.restitution = ") + value +
                     " from the calibration table " + path + source;
  const auto range =
      shape ? std::optional<MachRange>(training_mach_range(*shape)) : training_mach_range(t);
  const bool outside = range && !range->contains(s.freestream.mach);
  const std::string held = *e >= kMaxRestitution ? " past the elastic limit and held at e = 1" : "";
  if (outside)
    note += outside_warning(
        "Mach " + shortest(s.freestream.mach), "the table's training range", *range, "",
        "e(M) is extrapolated" + held + " and " +
            (!shape && wedge_deg && beyond_scatter_applies(t, s.freestream.mach)
                 ? extrapolation_measured(*t.angle_scatter_beyond, s.freestream.mach)
                 : std::string(kUnmeasuredError)));
  else if (!shape && wedge_deg && beyond_scatter_applies(t, s.freestream.mach))
    // Inside the training range, past the Mach numbers the inside scatter saw.
    note += "; " +
            extrapolation_measured(*t.angle_scatter_beyond, s.freestream.mach, "the table's own");
  // A fit in the deflection extrapolates beyond the training wedges too
  // (1/theta grows fast below them).
  const auto angles = training_angle_range(t);
  const RestitutionFit* chosen = t.model ? t.fit(*t.model) : nullptr;
  if (!shape && angle_deg && angles && chosen && uses_angle(chosen->model) &&
      !angles->contains(*angle_deg))
    note += outside_warning("the " + shortest(*angle_deg) + " deg deflection",
                            "the table's training range", *angles, " deg",
                            "e(M, theta) is extrapolated" + held + " and " + kUnmeasuredError);
  // A bow shock's prediction owes its band to the blunt training runs too:
  // charged to the bodies whose shock stands off in the gas (an attached
  // wedge whose granular shock detaches near the maximum deflection borrows
  // the scatter without that charge; its attached twins never use it).
  const bool stands_off = !angle_deg;  // a blunt body or a detached wedge
  // That scatter was measured on blunt bodies at a few Mach numbers; beyond
  // them the band's width is as unmeasured as e(M) is outside its range.
  const auto bow_range =
      !shape && stands_off && t.bow_shock ? training_mach_range(*t.bow_shock) : std::nullopt;
  const bool outside_bow = bow_range && !bow_range->contains(s.freestream.mach);
  if (outside_bow)
    note += outside_warning(
        "Mach " + shortest(s.freestream.mach),
        "the Mach numbers of the blunt bodies the bow-shock band's scatter was measured on,",
        *bow_range, "", kUnmeasuredError);
  bool outside_bias = false;
  if (bias) {
    note += "; its bow shock's fold taken out by the " + bias->shape + " shape's station bias (" +
            bias->model + ", trained on " + std::to_string(bias->bodies.size()) + " bodies)";
    const MachRange r{bias->mach_low, bias->mach_high};
    outside_bias = !r.contains(s.freestream.mach);
    if (outside_bias)
      note += outside_warning(
          "Mach " + shortest(s.freestream.mach),
          "the Mach numbers the station bias was trained on,", r, "",
          std::string("the bias is held at the nearest end and ") + kUnmeasuredError);
  }
  // The bow-shock scatter was measured on discs and capsules; on the one
  // detached wedge measured so far (M3/36) the granular shock stood 7x the
  // gas's standoff off (docs/shockfit.md, step 7).
  if (detached_wedge)
    note +=
        "; WARNING: no wedge beyond its maximum deflection is among the bow-shock training "
        "bodies, so this standoff's error is unmeasured (its band may miss the gas shock)";
  double cost =
      std::isfinite(bow) && stands_off ? t.cpu_seconds + t.bow_shock->cpu_seconds : t.cpu_seconds;
  if (bias && std::isfinite(bias->cpu_seconds)) cost += bias->cpu_seconds;
  AppliedCalibration out{note, cost, scatter, bow, outside || outside_bow || outside_bias};
  if (bias) out.station_bias = *bias;
  return out;
}

nlohmann::json run_prediction_at(const scene::Scene& s, double e, std::uint64_t seed,
                                 const std::string& out_dir, int np) {
  scene::Scene at = s;
  at.granular.restitution = e;
  at.granular.restitution_given = true;
  at.granular.seed = seed;
  auto r = run_prediction(at, out_dir, np);
  if (scene::interrupted())
    throw scene::RunError("calibrate interrupted; finished runs are cached, rerun to resume");
  return r;
}

nlohmann::json run_prediction(const scene::Scene& s, const std::string& out_dir, int np, bool force,
                              double angle_scatter_deg) {
  StageCache cache(out_dir);
  // A target taken from the mesh moves with the mesh and the levels, one
  // from the band with the table.
  const granular::PrecisionGoal goal = precision_goal(s, angle_scatter_deg);
  std::vector<std::string> parts{
      scene::section_yaml(s, "body"), scene::section_yaml(s, "freestream"),
      scene::section_yaml(s, "domain"), scene::section_yaml(s, "granular")};
  if (goal.active()) parts.push_back(nlohmann::json(goal.target).dump());
  // Stages cached before the averaging groups were written lack them.
  parts.push_back("groups 1");
  const std::string fp_g = fingerprint(parts);
  nlohmann::json gsum;
  scene::Lattice fields;
  std::vector<scene::Lattice> groups;
  if (!force && cache.fresh("granular", fp_g)) {
    gsum = cache.result("granular");
    fields = scene::read_vti(cache.dir("granular") + "/fields.vti");
    const std::string gpath = cache.dir("granular") + "/groups.vti";
    if (std::filesystem::is_regular_file(gpath))
      groups = scene::unpack_groups(scene::read_vti(gpath), gpath);
  } else {
    cache.invalidate("granular");
    granular::RunOptions go;
    go.out_dir = cache.dir("granular");
    go.np = np;
    const scene::CpuStopwatch cpu;
    auto r = granular::run_flow_scene(s, go, {}, goal);
    check_interrupt("the granular stage");
    if (r.summary.value("interrupted", false))
      throw scene::RunError("interrupted during the granular stage; rerun to resume");
    gsum = r.summary;
    gsum["stage_cpu_seconds"] = cpu.seconds();
    fields = std::move(r.fields);
    groups = std::move(r.groups);
    cache.mark_done("granular", fp_g, gsum);
  }
  const std::string fp_s = fingerprint({fp_g, scene::section_yaml(s, "shockfit")});
  nlohmann::json ssum;
  if (!force && cache.fresh("shockfit", fp_s)) {
    ssum = cache.result("shockfit");
  } else {
    cache.invalidate("shockfit");
    const scene::CpuStopwatch cpu;
    auto r = shockfit::locate_shock(s, fields);
    shockfit::apply_group_interval(s, groups, r);
    shockfit::write_outputs(s, fields, r, cache.dir("shockfit"));
    ssum = r.summary();
    const double position_half_width = shock_position_half_width(s, r);
    ssum["shock_position_half_width"] = std::isfinite(position_half_width)
                                            ? nlohmann::json(position_half_width)
                                            : nlohmann::json(nullptr);
    ssum["stage_cpu_seconds"] = cpu.seconds();
    cache.mark_done("shockfit", fp_s, ssum);
  }
  nlohmann::json out = ssum;
  out["granular_wall_seconds"] = gsum.value("wall_seconds", kNaN);
  out["granular_cpu_seconds"] = number_or_nan(gsum, "stage_cpu_seconds");
  out["shockfit_cpu_seconds"] = number_or_nan(ssum, "stage_cpu_seconds");
  out["predictor_cpu_seconds"] =
      number_or_nan(gsum, "stage_cpu_seconds") + number_or_nan(ssum, "stage_cpu_seconds");
  out["granular"] = gsum;
  out["fingerprint"] = fp_s;
  return out;
}

Prediction predict_shock(const scene::Scene& s, const std::string& predictor,
                         const std::string& out_dir, int np, bool force,
                         double calibration_angle_scatter_deg,
                         double calibration_bow_shock_relative_rms,
                         const BowStationBias* bow_station_bias) {
  const auto p = make_predictor(predictor);
  return p->predict({s, predictor_dir(out_dir, predictor), out_dir, np, force,
                     calibration_angle_scatter_deg, calibration_bow_shock_relative_rms,
                     bow_station_bias});
}

nlohmann::json run_pipeline(scene::Scene s, const RunOptions& o) {
  if (!s.body) throw scene::InputError(s.source_file + ": the pipeline needs a body scene");
  const auto predictor = make_predictor(o.predictor);  // unknown names fail before any work
  const auto t_start = std::chrono::steady_clock::now();
  scene::make_dirs(o.out_dir);
  const scene::DirLock lock(o.out_dir);
  const AppliedCalibration calib = apply_calibration(s, o.calibration_path);
  if (o.predictor == "granular")
    default_to_band_averaging(s, calib.angle_scatter_deg, calib.bow_shock_relative_rms);
  const double calib_cpu = o.predictor == "granular" ? calib.cpu_seconds : kNaN;
  const std::string& calib_note = calib.note;
  // Other predictors do not use the restitution: its note (and its warning
  // outside the training range) would only confuse their runs' terminal.
  if (!calib_note.empty() && o.predictor == "granular")
    scene::log_line("pipeline: " + calib_note, calib.outside_training_mach);
  scene::write_file_atomic(o.out_dir + "/scene.resolved.yaml", scene::to_yaml(s));
  const auto& levels = s.pipeline.levels;
  const int n_stages = 2 + (s.pipeline.cfd ? 2 : 1) * (2 * static_cast<int>(levels.size()) + 1) + 1;
  scene::Progress progress("pipeline", n_stages, "stages");
  int done = 0;
  auto step = [&](const std::string& what) { progress.update(++done, what); };
  GridRunner grids(s, o.out_dir, o.np, o.force, step);

  // The prediction: where the clustered grids put their fine band.
  const bool force_prediction =
      o.force.count("granular") || o.force.count("shockfit") || o.force.count("all");
  const Prediction pred =
      predictor->predict({s, predictor_dir(o.out_dir, o.predictor), o.out_dir, o.np,
                          force_prediction, calib.angle_scatter_deg, calib.bow_shock_relative_rms,
                          calib.station_bias ? &*calib.station_bias : nullptr});
  check_interrupt("the prediction");
  done = 2;
  step("prediction (" + o.predictor + ")");
  const ShockInput shock{
      pred.fingerprint, pred.shock_csv,
      !pred.size_fields.empty() || (pred.kind != scene::ShockKind::none && pred.curve.size() >= 2),
      pred.size_fields};

  // Both families, coarse to fine, interleaved level by level: a change in
  // the machine's load during the run then falls on both families alike.
  const PrimaryError primary = primary_error_for(s);
  std::vector<GridRun> fam_c, fam_u;
  if (!shock.has_shock)
    scene::log_line(
        "pipeline: the " + o.predictor + " predictor " +
            (pred.details.contains("no_band")
                 ? "placed no shock curve (" + pred.details["no_band"].get<std::string>() + ")"
                 : std::string("found no shock")) +
            "; no clustered grids, no verdict",
        true);
  GridVariant clustered_variant;
  for (const double level : levels) {
    fam_u.push_back(grids.run("uniform", level, {}, primary));
    if (!shock.has_shock) continue;
    fam_c.push_back(
        grids.run(clustered_family(o.predictor), level, shock, primary, clustered_variant));
    if (!clustered_variant.isotropic && strips_diverged(fam_c.back(), grids.robust_scheme())) {
      remesh_isotropic(grids, fam_c, shock, primary);
      clustered_variant.isotropic = true;
    }
  }
  one_scheme(grids, fam_c, shock, primary, clustered_variant);
  one_scheme(grids, fam_u, {}, primary);
  // The reference grid extends the uniform family: its scheme.
  const bool uniform_robust = family_scheme(fam_u) == grids.robust_scheme();
  const nlohmann::json convergence = reference_study(s, grids, primary, fam_u, uniform_robust);

  // Comparison, verdict and report.
  Reference ref = reference_for(s);
  if (!std::isfinite(ref.value) && !fam_u.empty()) ref.value = fam_u.back().value;
  for (auto& r : fam_c) score(r, ref);
  for (auto& r : fam_u) score(r, ref);
  const Comparison cmp = compare(fam_c, fam_u, pred.wall_seconds);
  Verdict verdict =
      make_verdict(primary, verdict_runs(fam_c), verdict_runs(fam_u), pred.cpu_seconds);
  charge_calibration(verdict, verdict_runs(fam_c), verdict_runs(fam_u), calib_cpu,
                     static_cast<int>(case_study_scenes().size()));
  ReportInputs in{
      s, o.out_dir, pred, ref, cmp, verdict, calib_note, seconds_since(t_start), convergence};
  nlohmann::json summary = make_summary(in);
  summary["calibration_outside_training_mach"] = calib.outside_training_mach;
  const std::string suffix = o.output_suffix.value_or("");
  scene::write_json_atomic(o.out_dir + "/summary" + suffix + ".json", summary);
  write_report(in, summary, "report" + suffix + ".md");
  step("report");
  progress.finish();
  return summary;
}

}  // namespace pipeline
