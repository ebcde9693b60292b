// pipeline: one command from a body scene to the clustered-vs-uniform verdict.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "pipeline/angle_scatter.hpp"
#include "pipeline/bow_shape_fit.hpp"
#include "pipeline/bow_shock_scatter.hpp"
#include "pipeline/cost_estimate.hpp"
#include "pipeline/league.hpp"
#include "pipeline/parametric.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/rejudge.hpp"
#include "pipeline/report.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/progress.hpp"
#include "scene/scene.hpp"
#include "scene/staging.hpp"

int main(int argc, char** argv) {
  scene::install_interrupt_handler();
  return scene::run_guarded("pipeline", [&]() -> int {
    CLI::App app{"pipeline: granular shock prediction -> clustered and uniform grids -> rhoCentralFoam -> report"};
    app.set_version_flag("--version", scene::version_string());
    app.require_subcommand(1);

    auto* run = app.add_subcommand("run", "run every stage on one scene (cached; rerun resumes)");
    std::string scene_path, out_dir, calibration;
    int np = 1;
    std::vector<std::string> force;
    bool dry_run = false;
    run->add_option("scene", scene_path, "scene YAML")->required();
    run->add_option("--out", out_dir, "output directory")->required();
    run->add_option("--np", np, "processes for granular replicas and OpenFOAM")->check(CLI::Range(1, 4096));
    run->add_option("--force", force, "rerun a stage: granular, shockfit, meshgen, cfd, all")
        ->check(CLI::IsMember({"granular", "shockfit", "meshgen", "cfd", "all"}));
    run->add_option("--calibration", calibration, "restitution table (default: pipeline/calibration.yaml)");
    run->add_flag("--dry-run", dry_run,
                  "validate the scene, print it resolved with every grid's estimated cells and CPU seconds, and stop");
    bool force_budget = false;
    run->add_flag("--force-budget", force_budget, "run even when the estimate exceeds pipeline.budget_cpu_seconds");
    std::string predictor = "granular";
    run->add_option("--predictor", predictor, "shock predictor: granular, correlation, coarse_cfd, adapt");

    auto* judge = app.add_subcommand(
        "verdict", "recompute a finished run's verdict from its recorded grids (RUNDIR/summary.json) with the "
                   "current method; writes RUNDIR/verdict.json, runs nothing");
    std::string judge_dir;
    judge->add_option("rundir", judge_dir, "a `pipeline run` output directory")->required();
    bool remeasure = false;
    judge->add_flag("--remeasure", remeasure,
                    "measure every grid's errors again from its CFD case with the current measures");

    auto* predict = app.add_subcommand("predict", "the shock predictor alone: shock.csv, summary.json, shock.png");
    pipeline::PredictOptions po;
    predict->add_option("scene", scene_path, "scene YAML")->required();
    predict->add_option("--predictor", po.predictor, "granular, correlation, coarse_cfd, adapt")->required();
    predict->add_option("--out", po.out_dir, "output directory")->required();
    predict->add_option("--np", po.np, "processes")->check(CLI::PositiveNumber);
    predict->add_option("--calibration", po.calibration_path, "restitution table (granular)");

    auto* league = app.add_subcommand("league", "every predictor against the uniform family, per scene (docs/league.md)");
    pipeline::LeagueOptions lo;
    league->add_option("scenes", lo.scenes, "scenes (default: the case studies)");
    league->add_option("--out", lo.out_dir, "output directory")->required();
    league->add_option("--predictor", lo.predictors, "predictors (default: all)");
    league->add_option("--docs", lo.docs_page, "page to write (default: docs/league.md)");
    league->add_option("--np", lo.np, "processes")->check(CLI::PositiveNumber);
    league->add_flag("--from-runs", lo.from_runs,
                     "write the page from the summaries already in --out, running nothing");

    auto* sweep = app.add_subcommand("sweep", "granular + shockfit over a parameter grid");
    std::vector<std::string> vary;
    int jobs = 1;
    sweep->add_option("scene", scene_path, "scene YAML")->required();
    sweep->add_option("--vary", vary, "KEY=v1,v2,... (repeatable; e.g. granular.restitution=0.8,0.9)")->required();
    sweep->add_option("--out", out_dir, "output directory")->required();
    sweep->add_option("--jobs", jobs, "cases at once (processes)")->check(CLI::Range(1, 256));
    sweep->add_option("--np", np, "threads per case")->check(CLI::Range(1, 1024));

    auto* calib = app.add_subcommand(
        "calibrate", "fit e(M[, theta]) so that granular shock angles match ideal-gas angles");
    pipeline::CalibrateOptions co;
    bool no_verify = false;
    double training_averaging = 0;
    calib->add_option(
        "--scene", co.scenes,
        "training wedge scenes (default: generated on --mach x --angle, case studies left out)");
    calib->add_option("--mach", co.machs, "Mach numbers of the generated training wedges")
        ->capture_default_str()
        ->delimiter(',');
    calib
        ->add_option("--angle", co.angles_deg, "deflections (deg) of the generated training wedges")
        ->capture_default_str()
        ->delimiter(',');
    calib->add_option("--e", co.restitutions, "restitution values to sweep")->delimiter(',');
    calib
        ->add_option("--refine", co.refinements,
                     "runs that bisect the bracketing e interval after the sweep")
        ->check(CLI::NonNegativeNumber);
    std::vector<std::string> from_points;
    calib->add_option("--from-points", from_points,
                      "fit from measured crossings instead of running: pipeline parametric's "
                      "parametric_calibration.json, a calibrate run's calibration.json, or a table "
                      "(.yaml), several joined; --out is then not needed");
    bool extend = false;
    calib
        ->add_flag("--extend", extend,
                   "with --from-points: the first file is a table being extended: keep its local "
                   "correction's widths (not chosen again by leave-one-out, so crossings added "
                   "beyond its range leave e inside it as it was) and its measured angle_scatter")
        ->needs("--from-points");
    std::vector<std::string> bow_runs;
    calib->add_option("--bow-shock-runs", bow_runs,
                      "finished `pipeline run` directories of blunt training bodies (no case study): "
                      "measure the granular bow shock's out-of-sample scatter under the table's e(M) "
                      "and write it into the table; runs nothing, --out not needed");
    std::vector<std::string> angle_runs;
    calib->add_option("--angle-check-runs", angle_runs,
                      "bench/calibration_oos/angle_check.sh directories (unseen wedges predicted "
                      "with the table at the default averaging): measure the table's own angle "
                      "error and write it as the table's angle_scatter, which attached bands then "
                      "take; runs nothing, --out not needed");
    bool fit_shapes = false;
    calib->add_flag(
        "--fit-shapes", fit_shapes,
        "with --bow-shock-runs: also fit each blunt shape's own e(M) on the runs' bodies "
        "(granular sweeps cached under --out; at least three bodies per shape; a shape "
        "none of the runs holds keeps the table's fit)");
    bool station_bias = false;
    calib->add_flag(
        "--station-bias", station_bias,
        "with --bow-shock-runs (runs at the table's blunt law): fit each blunt shape's station "
        "bias, the fold of its granular bow shock against the gas's along the body, with the "
        "standoff's own term, and write it into the table; the pooled scatter and shape fits "
        "stay as they are");
    int shape_seeds = pipeline::BowShapeOptions{}.seeds;
    calib
        ->add_option("--shape-seeds", shape_seeds,
                     "with --fit-shapes: granular runs per swept e, at seeds sharing no replica "
                     "(at most 10: an 11th would reach the left-out checks' seeds)")
        ->check(CLI::Range(1, pipeline::kMaxSweepSeeds));
    calib
        ->add_option("--seeds", co.seeds,
                     "granular runs per swept e on each training wedge, at seeds sharing no "
                     "replica, averaged (at most 10)")
        ->check(CLI::Range(1, pipeline::kMaxSweepSeeds));
    calib
        ->add_option("--averaging", training_averaging,
                     "flow-through times each generated training wedge averages (default 4, "
                     "the shipped table's; predict reads 12, docs/calibration.md)")
        ->check(CLI::Range(0.5, 64.0));
    calib->add_option("--out", co.out_dir, "output directory");
    calib->add_option("--table", co.table_path, "table to write (default: pipeline/calibration.yaml)");
    calib->add_option("--markdown", co.markdown_path,
                      "markdown tables to write (default: OUT/calibration.md)");
    calib->add_option("--np", co.np, "threads per run")->check(CLI::PositiveNumber);
    calib->add_flag("--no-verify", no_verify,
                    "skip the out-of-sample runs (leave-one-out and case studies at fresh seeds)");

    auto* studies = app.add_subcommand("studies", "regenerate the case studies and docs/case_studies.md");
    pipeline::StudiesOptions so;
    studies->add_option("--out", so.out_dir, "output directory")->required();
    studies->add_option("--scene", so.scenes, "scenes (default: pipeline/cases/*.yaml)");
    studies->add_option("--docs", so.docs_table, "summary table to write (default: docs/case_studies.md)");
    studies->add_option("--np", so.np, "processes")->check(CLI::PositiveNumber);

    auto* param = app.add_subcommand(
        "parametric", "granular parameter studies against the gas (docs/parametric.md)");
    pipeline::ParametricOptions pa;
    param->add_option("--out", pa.out_dir, "output directory (one cached directory per point)")
        ->required();
    param->add_flag("--quick", pa.quick,
                    "a reduced grid for a quick look (writes no docs unless --docs)");
    param->add_option("--budget-cpu-seconds", pa.budget_cpu_seconds,
                      "CPU seconds the grid is sized to (default 1200)");
    param->add_option("--jobs", pa.jobs, "points at once (processes)")->check(CLI::PositiveNumber);
    param->add_option("--docs", pa.docs_page,
                      "page to write (default: docs/parametric.md; - for none)");

    if (const auto code = scene::parse_cli(app, argc, argv)) return *code;

    if (run->parsed()) {
      scene::Scene s = scene::load_scene(scene_path);
      if (!s.body) throw scene::InputError(scene_path + ": the pipeline needs a body scene (this one has a box)");
      scene::require_supersonic(s, "the pipeline");
      scene::refuse_out_overlap(out_dir, scene_path, "scene file");
      pipeline::require_named_calibration(s, calibration);
      (void)pipeline::make_predictor(predictor);  // an unknown name is bad input, before any estimate
      const pipeline::BandScatter scatter = pipeline::band_scatter(s, predictor, calibration);
      if (const auto sized = pipeline::fit_default_sizes_to_budget(s, predictor, scatter))
        scene::log_line(*sized, true);
      const auto estimate = pipeline::estimate_run(s, predictor, scatter);
      if (dry_run) {
        std::cout << scene::to_yaml(s) << "\n" << pipeline::format_estimate(estimate, s.pipeline.budget_cpu_seconds);
        return 0;
      }
      pipeline::check_budget(s, estimate, force_budget);
      pipeline::RunOptions o;
      o.out_dir = out_dir;
      o.np = np;
      o.force = {force.begin(), force.end()};
      o.calibration_path = calibration;
      o.predictor = predictor;
      const auto summary = pipeline::run_pipeline(s, o);
      std::cout << summary.dump(2) << "\n";
      std::cout << pipeline::verdict_line(summary) << "\n";
      return 0;
    }
    if (judge->parsed()) {
      std::cout << pipeline::write_rejudged(judge_dir, remeasure) << "\n";
      return 0;
    }
    if (predict->parsed()) {
      const scene::Scene s = scene::load_scene(scene_path);
      pipeline::require_named_calibration(s, po.calibration_path);
      const auto j = pipeline::run_predict(s, po);
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    if (league->parsed()) {
      pipeline::run_league(lo);
      return 0;
    }
    if (sweep->parsed()) {
      std::vector<pipeline::Vary> v;
      for (const auto& a : vary) v.push_back(pipeline::parse_vary(a));
      pipeline::run_sweep(scene_path, v, {out_dir, jobs, np});
      return 0;
    }
    if (calib->parsed()) {
      if (fit_shapes && bow_runs.empty())
        throw scene::InputError(
            "calibrate: --fit-shapes needs --bow-shock-runs (the blunt training runs)");
      if (station_bias && (bow_runs.empty() || fit_shapes))
        throw scene::InputError(
            "calibrate: --station-bias needs --bow-shock-runs and no --fit-shapes (the bias "
            "belongs to the law the runs ran at)");
      if (station_bias) {
        std::cout << pipeline::calibrate_station_biases(bow_runs, co.table_path).dump(2) << "\n";
        return 0;
      }
      if (!bow_runs.empty()) {
        pipeline::BowShapeOptions shape_options;
        shape_options.cache_dir = co.out_dir;
        shape_options.np = co.np;
        shape_options.seeds = shape_seeds;
        std::cout << pipeline::calibrate_bow_shocks(bow_runs, co.table_path,
                                                    fit_shapes ? &shape_options : nullptr)
                         .dump(2)
                  << "\n";
        return 0;
      }
      if (!angle_runs.empty()) {
        std::cout << pipeline::calibrate_angle_scatter(angle_runs, co.table_path).dump(2) << "\n";
        return 0;
      }
      if (!from_points.empty()) {
        std::cout << pipeline::calibrate_from_points(from_points, co.table_path, extend).dump(2)
                  << "\n";
        return 0;
      }
      if (co.out_dir.empty()) throw scene::InputError("calibrate: --out is required (unless --from-points)");
      co.verify = !no_verify;
      if (calib->count("--averaging") > 0) co.averaging = training_averaging;
      const auto r = pipeline::run_calibration(co);
      std::cout << r.dump(2) << "\n";
      return 0;
    }
    if (param->parsed()) {
      if (pa.quick && pa.docs_page.empty()) pa.docs_page = "-";
      pipeline::run_parametric(pa);
      return 0;
    }
    if (studies->parsed()) {
      pipeline::run_studies(so);
      return 0;
    }
    return 2;
  });
}
