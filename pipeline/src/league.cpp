#include "pipeline/league.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "json_fields.hpp"
#include "pipeline/plot.hpp"
#include "pipeline/precision_goal.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/rejudge.hpp"
#include "pipeline/report.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "pipeline/verdict.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
using scene::kDeg;

// The shock the predictor is scored against: exact on attached wedges; for
// discs Billig's standoff, an empirical comparison; none otherwise.
nlohmann::json prediction_reference(const scene::Scene& s, const Prediction& p) {
  nlohmann::json r;
  if (const auto beta = scene::attached_shock_beta(s)) {
    r = {{"quantity", "shock_angle_deg"}, {"value", *beta / kDeg}, {"source", "theta-beta-Mach relation (exact)"}};
    r["error"] = std::abs(p.shock_angle_deg - *beta / kDeg);
  } else if (scene::correlation_is_exact_shape(*s.body)) {
    const double v = scene::billig_standoff_cylinder(s.freestream.mach) * scene::correlation_nose_radius(*s.body) /
                     scene::body_length(*s.body);
    r = {{"quantity", "standoff"}, {"value", v}, {"source", "Billig's cylinder correlation (a comparison)"}};
    r["relative_error"] = std::abs(p.standoff - v) / v;
  } else {
    r = nullptr;
  }
  return r;
}

void shock_picture(const scene::Scene& s, const Prediction& p, const std::string& png) {
  const auto g = scene::make_body(*s.body);
  PlotSpec spec{"Predicted shock (" + p.predictor + ") and the body", "x (body lengths)", "y (body lengths)",
                false, false, {}, {}};
  Series body, shock;
  body.title = "body";
  body.style = "lines lw 2";
  for (const auto& q : g.polyline) {
    body.x.push_back(q.x);
    body.y.push_back(q.y);
  }
  if (!g.polyline.empty()) {
    body.x.push_back(g.polyline.front().x);
    body.y.push_back(g.polyline.front().y);
  }
  shock.title = "shock +- 95% half-width";
  for (std::size_t i = 0; i < p.curve.size(); ++i) {
    shock.x.push_back(p.curve[i].x);
    shock.y.push_back(p.curve[i].y);
    shock.yerr.push_back(i < p.half_width.size() && std::isfinite(p.half_width[i]) ? p.half_width[i] : 0.0);
  }
  spec.series = {body, shock};
  spec.extra.push_back("set size ratio -1");
  plot_png(spec, png);
}
}  // namespace

nlohmann::json run_predict(scene::Scene s, const PredictOptions& o) {
  if (!s.body) throw scene::InputError(s.source_file + ": predict needs a body scene");
  (void)make_predictor(o.predictor);  // unknown names fail before any work
  scene::make_dirs(o.out_dir);
  const AppliedCalibration calib =
      o.predictor == "granular" ? apply_calibration(s, o.calibration_path) : AppliedCalibration{};
  // A bow shock's standoff is this command's product: it averages to its target.
  if (o.predictor == "granular") default_to_standoff_target(s);
  const Prediction p = predict_shock(s, o.predictor, o.out_dir, o.np, false,
                                     calib.angle_scatter_deg, calib.bow_shock_relative_rms,
                                     calib.station_bias ? &*calib.station_bias : nullptr);
  nlohmann::json j = p.summary();
  j["scene"] = s.name;
  j["reference"] = prediction_reference(s, p);
  if (!calib.note.empty()) j["calibration"] = calib.note;
  j["calibration_outside_training_mach"] = calib.outside_training_mach;
  if (calib.outside_training_mach) scene::log_line("pipeline: " + calib.note, true);
  const std::string csv = o.out_dir + "/shock.csv";
  if (fs::weakly_canonical(p.shock_csv) != fs::weakly_canonical(csv))
    fs::copy_file(p.shock_csv, csv, fs::copy_options::overwrite_existing);
  j["shock_csv"] = csv;
  shock_picture(s, p, o.out_dir + "/shock.png");
  scene::write_json_atomic(o.out_dir + "/summary.json", j);
  return j;
}

namespace {

// The granular family against each other predictor's family at the
// granular family's finest error, both families with their own predictor's
// CPU: "faster" means the granular route reaches that error in less total CPU.
void head_to_head(std::ostringstream& md, const nlohmann::json& row, const std::string& case_dir) {
  if (!row.contains("granular")) return;
  const nlohmann::json& g = row["granular"];
  const std::string g_path = case_dir + "/summary_granular.json";
  const PrimaryError primary{g.value("primary_error", ""), "", ""};
  const auto mine = recorded_family(g, g_path, clustered_family("granular"));
  const double mine_cpu = number_or_nan(g["verdict_details"], "predictor_cpu_seconds");
  std::ostringstream rows;
  for (const auto& [name, sum] : row.items()) {
    if (name == "granular") continue;
    const auto other = recorded_family(sum, case_dir + "/summary_" + name + ".json", clustered_family(name));
    const double other_cpu = number_or_nan(sum["verdict_details"], "predictor_cpu_seconds");
    if (other.empty() || !std::isfinite(mine_cpu) || !std::isfinite(other_cpu)) {
      rows << "| " << name << " | n/a (no clustered grids) | n/a | n/a |\n";
      continue;
    }
    const Verdict v = make_verdict(primary, mine, other, mine_cpu, other_cpu);
    rows << "| " << name << " | " << speedup_text(interval_json(v.speedup_total)) << " | "
         << speedup_text(interval_json(v.speedup_cfd)) << " | "
         << v.verdict << " |\n";
  }
  if (rows.str().empty()) return;
  md << "\nHead to head: the other predictor's family over the granular family, total CPU (each with its own "
        "predictor's cost) and CFD CPU at the granular family's finest " << primary.name
     << "; `faster` means the granular route is faster.\n\n| against | total CPU other / granular (95%) | CFD CPU "
        "other / granular (95%) | granular route |\n|---|---|---|---|\n"
     << rows.str() << "\n";
}

}  // namespace

nlohmann::json run_league(const LeagueOptions& o) {
  const std::vector<std::string> scenes = o.scenes.empty() ? case_study_scenes() : o.scenes;
  const std::vector<std::string> preds = o.predictors.empty() ? predictor_names() : o.predictors;
  for (const auto& n : preds) (void)make_predictor(n);
  std::vector<scene::Scene> parsed;
  for (const auto& p : scenes) parsed.push_back(scene::load_scene(p));
  scene::make_dirs(o.out_dir);
  nlohmann::json all = nlohmann::json::object();
  std::ostringstream md;
  md << "# The league: which predictor earns its clustered grid\n\n"
     << "Regenerated by `pipeline league --out " << o.out_dir
     << "`. For each case, every predictor places the shock band of a clustered family; each family is compared "
        "with the same uniform family at equal primary error (docs/verdict.md): CPU seconds, 95% intervals, "
        "`faster` / `slower` only when the interval excludes 1. Predictor error: against the exact oblique shock "
        "on wedges, against Billig's correlation on discs (a comparison), none on other bodies.\n\n";
  for (const auto& s : parsed) {
    if (scene::interrupted()) break;
    md << "## " << s.name << "\n\n| predictor | predictor CPU s | prediction | predictor error | "
          "speedup CFD CPU | speedup total CPU | verdict |\n|---|---|---|---|---|---|---|\n";
    nlohmann::json row = nlohmann::json::object();
    PlotSpec fig{"Primary error against total CPU time: " + s.name, "total CPU seconds (predictor + meshing + CFD)",
                 "primary error", true, true, {}, {}};
    bool uniform_drawn = false;
    std::string best;
    double best_speedup = 0;
    for (const auto& name : preds) {
      RunOptions ro;
      ro.out_dir = o.out_dir + "/" + s.name;
      ro.np = o.np;
      ro.predictor = name;
      ro.output_suffix = "_" + name;
      nlohmann::json sum;
      try {
        sum = o.from_runs ? read_run_summary(ro.out_dir + "/summary_" + name + ".json",
                                             "no recorded summary (run `pipeline league` without --from-runs first)")
                           : run_pipeline(s, ro);
      } catch (const scene::RunError& e) {
        scene::log_line("pipeline league: " + s.name + " / " + name + ": " + e.what(), true);
        md << "| " << name << " | failed: " << e.what() << " | | | | | |\n";
        continue;
      }
      const auto& pr = sum["prediction"];
      const bool angle = sum["reference"].value("quantity", "") == "shock_angle_deg";
      const std::string value = angle ? format_number(number_or_nan(pr, "shock_angle_deg"), 4) + " deg"
                                      : format_number(number_or_nan(pr, "standoff"), 4) + " L";
      const std::string err = angle ? format_number(number_or_nan(pr, "error_deg"), 3) + " deg"
                                    : (sum["reference"].value("source", "").find("Billig") != std::string::npos &&
                                               std::isfinite(number_or_nan(pr, "relative_error"))
                                           ? format_number(100 * number_or_nan(pr, "relative_error"), 3) + "% (Billig)"
                                           : "n/a");
      md << "| " << name << " | " << format_number(number_or_nan(pr, "cpu_seconds"), 3) << " | " << value << " | " << err << " | "
         << speedup_text(sum["speedup_cfd"]) << " | " << speedup_text(sum["speedup_total"]) << " | "
         << sum.value("verdict", "n/a") << " |\n";
      const double st = number_or_nan(sum["speedup_total"], "value");
      if (std::isfinite(st) && st > best_speedup) {
        best_speedup = st;
        best = name;
      }
      Series c, u;
      c.title = "clustered (" + name + ")";
      u.title = "uniform";
      for (const auto& r : sum["runs"]) {
        const double e = number_or_nan(r, "primary_error"), cpu = number_or_nan(r, "cpu_seconds"), mesh = number_or_nan(r, "mesh_cpu_seconds");
        if (!(e > 0) || !(cpu > 0)) continue;
        const bool clustered = r.value("family", "") != "uniform";
        Series& ser = clustered ? c : u;
        ser.x.push_back(cpu + (std::isfinite(mesh) ? mesh : 0.0) + (clustered ? number_or_nan(pr, "cpu_seconds") : 0.0));
        ser.y.push_back(e);
      }
      fig.series.push_back(c);
      if (!uniform_drawn) {
        fig.series.push_back(u);
        uniform_drawn = true;
      }
      row[name] = sum;
    }
    head_to_head(md, row, o.out_dir + "/" + s.name);
    const std::string png = o.out_dir + "/" + s.name + "/league.png";
    plot_png(fig, png);
    md << "\n";
    if (best.empty())
      md << "No predictor gave a speedup that could be fitted.\n\n";
    else
      md << "Highest total-CPU speedup: **" << best << "** (" << format_number(best_speedup) << "x); see the verdict column "
         << "for whether it is distinguishable from 1. Figure: `" << png << "`.\n\n";
    all[s.name] = row;
  }
  scene::write_json_atomic(o.out_dir + "/league.json", all);
  const std::string page = o.docs_page.empty() ? std::string(PIPELINE_SOURCE_DIR) + "/../docs/league.md" : o.docs_page;
  scene::write_file_atomic(page, md.str());
  scene::write_file_atomic(o.out_dir + "/league.md", md.str());
  return all;
}

}  // namespace pipeline
