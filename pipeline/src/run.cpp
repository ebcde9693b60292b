#include "pipeline/run.hpp"

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
#include "pipeline/report.hpp"
#include "pipeline/stage_cache.hpp"
#include "scene/body.hpp"
#include "scene/cli.hpp"
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
    r.source = "Billig's correlation for cylinders";
    r.value = scene::billig_standoff_cylinder(s.freestream.mach);  // in radii = body lengths
  } else {
    r.source = "finest uniform grid";
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
  s.granular.restitution = *e;
  char buf[400];
  std::snprintf(buf, sizeof buf, "granular.restitution = %.4f from the calibration table %s%s", *e, path.c_str(),
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
    auto r = granular::run_flow_scene(s, go);
    check_interrupt("the granular stage");
    if (r.summary.value("interrupted", false))
      throw scene::RunError("interrupted during the granular stage; rerun to resume");
    gsum = r.summary;
    fields = std::move(r.fields);
    cache.mark_done("granular", fp_g, gsum);
  }
  const std::string fp_s = fingerprint({fp_g, scene::section_yaml(s, "shockfit")});
  nlohmann::json ssum;
  if (!force && cache.fresh("shockfit", fp_s)) {
    ssum = cache.result("shockfit");
  } else {
    cache.invalidate("shockfit");
    const auto r = shockfit::locate_shock(s, fields);
    shockfit::write_outputs(s, fields, r, cache.dir("shockfit"));
    ssum = r.summary();
    cache.mark_done("shockfit", fp_s, ssum);
  }
  nlohmann::json out = ssum;
  out["granular_wall_seconds"] = gsum.value("wall_seconds", kNaN);
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
  StageCache cache(o.out_dir);
  const auto& levels = s.pipeline.levels;
  const int n_stages = 2 + (s.pipeline.cfd ? 4 : 2) * static_cast<int>(levels.size()) + 1;
  scene::Progress progress("pipeline", n_stages, "stages");
  int done = 0;
  auto step = [&](const std::string& what) { progress.update(++done, what); };

  // 1-2: granular prediction and its shock.
  if (forced(o, "granular")) cache.invalidate("granular");
  if (forced(o, "shockfit")) cache.invalidate("shockfit");
  const auto pred = run_prediction(s, o.out_dir, o.np);
  check_interrupt("shockfit");
  done = 2;
  step("granular + shockfit");
  const std::string shock_csv = cache.dir("shockfit") + "/shock.csv";
  const std::string fp_s = pred["fingerprint"];

  // 3: grids and CFD runs, coarse to fine, both families.
  const Reference ref0 = reference_for(s);
  std::vector<GridRun> fam_c, fam_u;
  for (const std::string family : {"uniform", "clustered"}) {
    for (const double level : levels) {
      const std::string name = level_name(family, level);
      const std::string mstage = "meshgen/" + name, cstage = "cfd/" + name;
      const bool clustered = family == "clustered";
      if (clustered && pred.value("shock", "none") == "none") {
        scene::log_line("pipeline: no granular shock found; clustered grid " + name + " skipped", true);
        continue;
      }
      const std::string fp_m = fingerprint({clustered ? fp_s : "", scene::section_yaml(s, "body"),
                                            scene::section_yaml(s, "domain"), scene::section_yaml(s, "mesh"),
                                            family, std::to_string(level)});
      if (forced(o, "meshgen")) cache.invalidate(mstage);
      nlohmann::json msum;
      if (cache.fresh(mstage, fp_m)) {
        msum = cache.result(mstage);
      } else {
        cache.invalidate(mstage);
        meshgen::MeshRequest req = clustered ? meshgen::request_from_shock_csv(shock_csv) : meshgen::MeshRequest{};
        req.uniform = !clustered;
        req.h_min = s.mesh.h_min * level;
        req.h_max = clustered ? s.mesh.h_max * level : s.mesh.h_min * level;
        const auto m = meshgen::generate_mesh(s, req, cache.dir(mstage));
        msum = m.summary();
        msum["seconds"] = m.seconds;
        cache.mark_done(mstage, fp_m, msum);
      }
      check_interrupt("meshgen " + name);
      step("mesh " + name);
      GridRun run;
      run.family = family;
      run.level = level;
      run.cells = msum.value("cells", 0L);
      run.mesh_seconds = msum.value("seconds", 0.0);
      if (s.pipeline.cfd) {
        const std::string fp_c = fingerprint({fp_m, scene::section_yaml(s, "cfd"), scene::section_yaml(s, "freestream")});
        if (forced(o, "cfd")) cache.invalidate(cstage);
        nlohmann::json csum;
        if (cache.fresh(cstage, fp_c)) {
          csum = cache.result(cstage);
        } else {
          cache.invalidate(cstage);
          cfd::CaseOptions co;
          co.np = o.np;
          const auto c = cfd::run_case(s, cache.dir(mstage), cache.dir(cstage), co);
          check_interrupt("cfd " + name);
          const auto lat = cfd::resample_to_lattice(s, cache.dir(cstage), s.granular.lattice_nx, s.granular.lattice_ny);
          scene::write_vti(lat, cache.dir(cstage) + "/fields.vti");
          csum = c.summary();
          cache.mark_done(cstage, fp_c, csum);
        }
        // The CFD shock is located like the granular one, with the shock
        // window widened to the grid's smeared shock (same rule for both families).
        const scene::Scene fs_scene = cfd_shockfit_scene(s, level * s.mesh.h_min);
        const std::string fstage = cstage + "/shockfit";
        const std::string fp_f = fingerprint({fp_c, scene::section_yaml(fs_scene, "shockfit")});
        nlohmann::json fsum;
        if (!forced(o, "cfd") && cache.fresh(fstage, fp_f)) {
          fsum = cache.result(fstage);
        } else {
          cache.invalidate(fstage);
          const auto lat = scene::read_vti(cache.dir(cstage) + "/fields.vti");
          const auto sh = shockfit::locate_shock(fs_scene, lat);
          shockfit::write_outputs(fs_scene, lat, sh, cache.dir(fstage));
          fsum = sh.summary();
          fsum["shock_value"] = shock_value(sh);
          fsum["shock_value_ci"] = shock_ci(sh);
          cache.mark_done(fstage, fp_f, fsum);
        }
        run.cfd_wall_seconds = csum.value("wall_seconds", kNaN);
        run.steps = csum.value("steps", 0L);
        run.steady = csum.value("steady_state_reached", false);
        run.shock = fsum.value("shock", "none");
        run.value = fsum["shock_value"].is_number() ? fsum["shock_value"].get<double>() : kNaN;
        run.value_ci = fsum["shock_value_ci"].is_number() ? fsum["shock_value_ci"].get<double>() : kNaN;
        run.wall_pressure_ratio =
            csum["wall_pressure_ratio"].is_number() ? csum["wall_pressure_ratio"].get<double>() : kNaN;
        step("cfd " + name);
      }
      (clustered ? fam_c : fam_u).push_back(run);
    }
  }

  // 4: comparison and report.
  Reference ref = ref0;
  if (!std::isfinite(ref.value) && !fam_u.empty()) ref.value = fam_u.back().value;
  for (auto& r : fam_c) score(r, ref);
  for (auto& r : fam_u) score(r, ref);
  const double granular_seconds = pred.value("granular_wall_seconds", 0.0);
  const Comparison cmp = compare(fam_c, fam_u, granular_seconds);
  ReportInputs in{s, o.out_dir, pred, ref, cmp, calib_note, seconds_since(t_start)};
  const nlohmann::json summary = make_summary(in);
  scene::write_json_atomic(o.out_dir + "/summary.json", summary);
  write_report(in, summary);
  step("report");
  progress.finish();
  return summary;
}

}  // namespace pipeline
