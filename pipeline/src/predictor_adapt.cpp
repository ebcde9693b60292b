// What a CFD engineer would do with a coarse solution instead of a shock
// curve: adapt the grid to it. The coarse uniform run of coarse_cfd (the
// same cached case), its density resampled on a lattice at half the coarse
// cell size, the Hessian's largest |eigenvalue| as an isotropic metric
// (hessian_size.hpp, docs/adapt.md), and one size field per family level:
// the smallest cell h_min x level, the largest h_max x level, graded at
// mesh.growth like every other grid. One adaptation cycle. The coarse run's
// CPU seconds and the fields' are the prediction's cost.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "cfd/run_case.hpp"
#include "pipeline/hessian_size.hpp"
#include "pipeline/predictors.hpp"
#include "pipeline/stage_cache.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"

namespace pipeline {

namespace {
// The interpolation error is controlled in L^2 (h ~ lambda^(-1/3)): a shock
// and a smooth expansion both get cells, where L^infinity would spend them
// all at the shock.
constexpr double kNormP = 2.0;
// Lattice cells per coarse grid cell: the resampled solution is piecewise
// constant per grid cell; two samples per cell and one 1-2-1 pass turn its
// steps into slopes the central differences can read.
constexpr double kLatticePerGridCell = 2.0;
constexpr int kSmoothingPasses = 1;

std::string level_file(const std::string& dir, double level) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "/size_h%g.vti", level);
  return dir + buf;
}
}  // namespace

Prediction AdaptPredictor::predict(const PredictContext& cx) const {
  Prediction p = CoarseCfdPredictor{}.predict(cx);
  const auto t0 = std::chrono::steady_clock::now();
  const scene::CpuStopwatch cpu;
  const scene::Scene& s = cx.scene;
  const double L = scene::body_length(*s.body);
  const double coarse_level = p.details.at("level").get<double>();
  const std::string case_dir = p.details.at("case_dir").get<std::string>();

  // The coarse density on a lattice over the scene's domain.
  const scene::Domain d = scene::scene_domain(s);
  const double spacing = s.mesh.h_min * coarse_level * L / kLatticePerGridCell;
  const int nx = std::max(3, static_cast<int>(std::lround(d.width() / spacing)));
  const int ny = std::max(3, static_cast<int>(std::lround(d.height() / spacing)));
  const scene::Lattice solution = cfd::resample_to_lattice(s, case_dir, nx, ny);
  const scene::Lattice lambda = hessian_magnitude(solution, "rho", kSmoothingPasses);

  nlohmann::json levels = nlohmann::json::array();
  std::vector<std::string> parts{"adapt", p.fingerprint};
  for (const double level : s.pipeline.levels) {
    SizeTarget t;
    t.h_min = s.mesh.h_min * level * L;
    t.h_max = s.mesh.h_max * level * L;
    t.growth = s.mesh.growth;
    t.norm_p = kNormP;
    scene::Lattice sizes = size_from_hessian(lambda, t);
    const double complexity = lattice_complexity(sizes);
    for (double& h : sizes.fields.at("h")) h /= L;  // meshgen reads body lengths
    sizes.fields["lambda"] = lambda.field("lambda");
    const std::string path = level_file(cx.out_dir, level);
    scene::write_vti(sizes, path);
    p.size_fields.emplace_back(level, path);
    parts.push_back(scene::read_file(path));
    levels.push_back({{"level", level}, {"path", path}, {"complexity", complexity}});
  }
  p.predictor = name();
  p.fingerprint = fingerprint(parts);
  const double field_cpu = cpu.seconds();
  p.cpu_seconds += field_cpu;
  p.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  p.details["coarse_cpu_seconds"] = p.cpu_seconds - field_cpu;
  p.details["size_field_cpu_seconds"] = field_cpu;
  p.details["metric"] =
      "largest |eigenvalue| of the density Hessian, L^p-optimal isotropic size (docs/adapt.md)";
  p.details["norm_p"] = kNormP;
  p.details["lattice"] = {nx, ny};
  p.details["smoothing_passes"] = kSmoothingPasses;
  p.details["adaptation_cycles"] = 1;
  p.details["size_fields"] = levels;
  return p;
}

}  // namespace pipeline
