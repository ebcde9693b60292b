// The coarse_cfd predictor with real gmsh and OpenFOAM (slow).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/predictor.hpp"
#include "pipeline/run.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace fs = std::filesystem;

namespace {
using scene::kDeg;
const std::string kData = std::string(SOURCE_DIR) + "/tests/data";
}  // namespace

// A coarse uniform CFD solution located by shockfit: the shock within a
// coarse grid's reach of theta-beta-Mach, its cost counted.
TEST(PredictorSlow, CoarseCfdLocatesTheWedgeShock) {
  auto s = scene::load_scene(kData + "/wedge_verdict.yaml");
  s.pipeline.levels = {4.0};
  const fs::path dir = fs::temp_directory_path() / "shockgrain_predictor_coarse_cfd";
  fs::remove_all(dir);
  const auto p = pipeline::predict_shock(s, "coarse_cfd", dir.string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::attached);
  constexpr double kCoarseGridTolDeg = 1.5;  // ~320 cells: the shock spans 3-4 cells of h = 0.06
  EXPECT_NEAR(p.shock_angle_deg, *scene::oblique_shock_beta(3.0, 10 * kDeg, 1.4) / kDeg, kCoarseGridTolDeg);
  EXPECT_GT(p.cpu_seconds, 0.0);
  EXPECT_GE(p.curve.size(), 2u);
  EXPECT_TRUE(fs::exists(dir / "cfd" / "uniform_h4" / "summary.json")) << "the grid is the uniform family's coarsest";
}
