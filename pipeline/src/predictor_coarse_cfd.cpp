// What a CFD engineer would do without a granular gas: solve on a coarse
// uniform grid, locate the shock on that solution with the same two-line
// fits, and cluster the next grids there. The grid is the uniform family's
// coarsest level (the largest of pipeline.levels), so inside `pipeline run`
// it is the same cached case as that family member; its CPU seconds are
// counted in full as the prediction's cost all the same.
#include "pipeline/predictors.hpp"

#include <algorithm>
#include <cmath>

#include "pipeline/grid_runs.hpp"
#include "pipeline/stage_cache.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"

namespace pipeline {

Prediction CoarseCfdPredictor::predict(const PredictContext& cx) const {
  const scene::Scene& s = cx.scene;
  if (s.pipeline.levels.empty()) throw scene::InputError(s.source_file + ": pipeline.levels: empty");
  const double level = *std::max_element(s.pipeline.levels.begin(), s.pipeline.levels.end());
  scene::Scene solve_scene = s;
  solve_scene.pipeline.cfd = true;
  GridRunner grids(solve_scene, cx.run_dir, cx.np, cx.force ? std::set<std::string>{"all"} : std::set<std::string>{});
  const GridRun run = grids.run("uniform", level, {}, primary_error_for(s));
  Prediction p;
  p.predictor = name();
  p.kind = scene::shock_kind_from(run.shock);
  p.cpu_seconds = run.mesh_cpu_seconds + run.cfd_cpu_seconds;
  p.wall_seconds = run.mesh_seconds + run.cfd_wall_seconds;
  if (p.kind == scene::ShockKind::attached) {
    p.shock_angle_deg = run.value;
    p.shock_angle_ci_deg = run.value_ci;
  } else if (p.kind == scene::ShockKind::detached) {
    p.standoff = run.value;
    p.standoff_ci = run.value_ci;
  }
  const std::string located = grids.case_dir("uniform", level) + "/shockfit/shock.csv";
  if (p.kind != scene::ShockKind::none)
    for (const auto& q : read_accepted_shock(located)) {
      p.curve.push_back(q.point);
      p.half_width.push_back(q.half_width);
    }
  scene::make_dirs(cx.out_dir);
  p.shock_csv = cx.out_dir + "/shock.csv";
  write_shock_curve(p.shock_csv, p.curve, p.half_width);
  p.fingerprint = fingerprint({"coarse_cfd", scene::read_file(p.shock_csv)});
  p.details = {{"grid", level_name("uniform", level)}, {"level", level}, {"cells", run.cells},
               {"case_dir", grids.case_dir("uniform", level)},
               {"steady_state_reached", run.steady}, {"cfd_cpu_seconds", run.cfd_cpu_seconds},
               {"mesh_cpu_seconds", run.mesh_cpu_seconds},
               {"why_this_level", "the uniform family's coarsest level: the cheapest CFD solution the engineer "
                                  "already runs, its cost reported beside the granular stage's"}};
  return p;
}

}  // namespace pipeline
