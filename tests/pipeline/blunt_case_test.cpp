// The blunt-body measures on a real coarse case (slow; gmsh and OpenFOAM):
// the Mach 4 disc of the case studies on its uniform h = 0.08 grid.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cfd/run_case.hpp"
#include "meshgen/mesh.hpp"
#include "pipeline/bow_shock_check.hpp"
#include "pipeline/error_measures.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace {
namespace fs = std::filesystem;

// The case study's grid at this size (docs/verdict.md, blunt bodies): the
// fitted stagnation pressure 1.7 % off Rayleigh's with a 1.2 % wander over
// its last writes; this test's fresh grid (3379 cells) gave 1.8 % with a
// 2.0 % wander. 4 % bounds both: the stagnation point's own floor on these
// grids, not a convergence claim.
constexpr double kPitotTol = 0.04;
// Its forebody total-enthalpy L1 was 0.0016 (this test's grid: 0.0019); the coarsest study grid
// (h = 0.16) gave 0.0029, so a value above that means a broken solution.
constexpr double kMaxTotalEnthalpyL1 = 0.0029;
constexpr double kGridSize = 0.08;

TEST(BluntCase, DiscMach4CoarseGridMeetsPitotAndHasASmoothShockAtTheAxis) {
  const scene::Scene s = scene::parse_scene(
      "name: disc_M4\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n"
      "domain: {xmin: -1.53365831425246, xmax: 0.5, ymin: 0, ymax: 2.50975669227997, symmetric: "
      "true}\n");
  const fs::path d = test_support::scratch_root() / "pipeline_blunt_case";
  fs::remove_all(d);
  fs::create_directories(d);
  meshgen::MeshRequest req;
  req.uniform = true;
  req.h_min = kGridSize;
  meshgen::generate_mesh(s, req, (d / "mesh").string());
  const cfd::CaseResult r = cfd::run_case(s, (d / "mesh").string(), (d / "case").string(), {});
  ASSERT_TRUE(r.steady_state_reached);

  const pipeline::CaseErrors e = pipeline::measure_case_errors(s, (d / "case").string());
  const double pitot = scene::rayleigh_pitot_ratio(4.0, 1.4);
  EXPECT_NEAR(e.stagnation_pressure_ratio, pitot, kPitotTol * pitot);
  EXPECT_TRUE(std::isfinite(e.stagnation_pressure.uncertainty));
  EXPECT_GT(e.l1_total_enthalpy.value, 0.0);
  EXPECT_LT(e.l1_total_enthalpy.value, kMaxTotalEnthalpyL1);
  // The carbuncle check finds the shock and finds it smooth.
  ASSERT_TRUE(std::isfinite(e.shock_axis_deviation_cells));
  EXPECT_LT(e.shock_axis_deviation_cells, pipeline::kCarbuncleCells);
}

}  // namespace
