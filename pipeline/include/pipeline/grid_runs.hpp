#pragma once
// One grid of a family, from mesh to measured error: gmsh (clustered at a
// predicted shock, or uniform), rhoCentralFoam to steady state, the CFD
// shock located by shockfit, the exact-reference errors. Each step is a
// cached stage under the run's directory, with its CPU seconds recorded.
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/compare.hpp"
#include "pipeline/stage_cache.hpp"
#include "pipeline/verdict.hpp"
#include "scene/scene.hpp"

namespace pipeline {

// What clustered grids need of a prediction.
struct ShockInput {
  std::string fingerprint;  // clustered grids are remade when it changes
  std::string shock_csv;
  bool has_shock = false;
  // Per level, a size field meshed instead of the band round shock_csv
  // (predictors that size grids themselves: Prediction::size_fields).
  std::vector<std::pair<double, std::string>> size_fields;
};

// A grid's CFD shock of the other kind than the flow's (`shock_kind` as
// shockfit names it: shockfit read a detached wedge's near-normal bow shock
// as an attached 72 deg line) measures nothing comparable: the note the
// report shows, or nothing when the kinds agree or no shock was found.
std::optional<std::string> foreign_shock_note(const scene::Scene& s, const std::string& shock_kind);

// How a grid departs from the scene's own settings, each its own cached
// stage beside the scene's (the suffix on its name).
struct GridVariant {
  bool isotropic = false;  // mesh.anisotropy 1: no shock-aligned strips in the band
  bool robust = false;     // the robust cfd settings from the start (cfd::robust_settings)
  std::string mesh_suffix() const { return isotropic ? "_isotropic" : ""; }
  std::string case_suffix() const { return mesh_suffix() + (robust ? "_robust" : ""); }
};

class GridRunner {
 public:
  // `force`: stages to rerun (meshgen, cfd, all). `on_step` hears each
  // finished mesh and solve (progress).
  GridRunner(const scene::Scene& s, const std::string& out_dir, int np, std::set<std::string> force,
             std::function<void(const std::string&)> on_step = {});

  // family: "uniform", "reference" (uniform, in neither family) or
  // "clustered..." (around `shock`). Meshes, and unless the scene's
  // pipeline.cfd is false, solves, locates the CFD shock and measures.
  // `variant`: meshed or solved otherwise than the scene says (GridVariant).
  GridRun run(const std::string& family, double level, const ShockInput& shock,
              const PrimaryError& primary, GridVariant variant = {});

  // The scheme (flux/limiter) a robust run carries.
  std::string robust_scheme() const;

  // The stage directory of a grid's CFD case and mesh.
  std::string case_dir(const std::string& family, double level) const;
  std::string mesh_dir(const std::string& family, double level) const;

 private:
  nlohmann::json mesh(const std::string& family, double level, const ShockInput& shock,
                      const GridVariant& v);
  const scene::Scene& scene_for(const GridVariant& v) const;
  // Stages meshgen/MESH_NAME and cfd/CASE_NAME: the grid's name with its
  // variant's suffixes.
  nlohmann::json solve(const std::string& mesh_name, const std::string& case_name,
                       const scene::Scene& cs, const std::string& fp_mesh);
  nlohmann::json locate(const std::string& case_name, double level, const std::string& fp_cfd);
  void measure(const std::string& case_name, const PrimaryError& primary, GridRun& run) const;
  void drop_foreign_shock(GridRun& run) const;
  bool forced(const std::string& stage) const;

  const scene::Scene& s_;
  // s_ with the robust cfd settings, with isotropic bands, and with both.
  scene::Scene robust_, isotropic_, isotropic_robust_;
  StageCache cache_;
  int np_;
  std::set<std::string> force_;
  std::function<void(const std::string&)> on_step_;
};

std::string level_name(const std::string& family, double level);

// The scheme a CFD case summary's result carries: "flux/limiter".
std::string case_scheme(const nlohmann::json& cfd_summary);

// RunError naming the step when Ctrl-C was pressed: finished stages stay cached.
void check_interrupt(const std::string& where);

// Level of the independent reference grid: pipeline.reference_level, else
// the coarsest level finer than every family member whose 2x and 4x coarser
// levels are both family levels (a Richardson triple at ratio 2: 0.7 for the
// default levels, three times the finest grid's cost rather than the eight
// times of half the finest level), else half the finest level.
double reference_grid_level(const scene::PipelineParams& p);
// Levels equal within a relative slack (they are user numbers: 2.8, 1.4).
bool same_level(double a, double b);

}  // namespace pipeline
