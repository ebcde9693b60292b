// The precision target a scene asks for and the shock position half-width
// it is compared with (no granular run).
#include "pipeline/precision_goal.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace {

scene::Scene wedge(const std::string& granular_section) {
  return scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 2.0}\nfreestream: {mach: 3}\n"
      "mesh: {h_min: 0.02}\npipeline: {levels: [2, 1.4, 0.5]}\ngranular: " +
      granular_section + "\n");
}

}  // namespace

TEST(PrecisionGoal, TargetFromTheSceneOrTheFinestGrid) {
  EXPECT_FALSE(pipeline::precision_target(wedge("{}")).has_value());
  EXPECT_FALSE(pipeline::precision_goal(wedge("{}")).active());
  EXPECT_DOUBLE_EQ(*pipeline::precision_target(wedge("{target_half_width: 0.005}")), 0.005);
  // mesh: k h_min at the finest level (0.5).
  const scene::Scene m = wedge("{target_half_width: mesh}");
  EXPECT_DOUBLE_EQ(*pipeline::precision_target(m), pipeline::kTargetFineCells * 0.02 * 0.5);
  const granular::PrecisionGoal g = pipeline::precision_goal(m);
  EXPECT_TRUE(g.active());
  EXPECT_DOUBLE_EQ(g.target, pipeline::kTargetFineCells * 0.01);
  // The resolved scene keeps the choice.
  EXPECT_TRUE(scene::parse_scene(scene::to_yaml(m)).granular.target_from_mesh);
}

TEST(PrecisionGoal, AttachedHalfWidthIsTheFarEndDisplacement) {
  // Nose at the origin; the farthest accepted point 3 scene units away on a
  // body of length 2: 1.5 body lengths, times tan(ci).
  const scene::Scene s = wedge("{}");
  shockfit::ShockResult r;
  r.shock = scene::ShockKind::attached;
  r.shock_angle_ci_deg = 0.5;
  shockfit::StationFit near, far, rejected;
  near.accepted = far.accepted = true;
  near.shock = {1.0, 0.3};
  far.shock = {3.0 * std::cos(0.6), 3.0 * std::sin(0.6)};
  rejected.shock = {10.0, 5.0};  // not accepted: not part of the shock
  r.stations = {near, far, rejected};
  EXPECT_NEAR(pipeline::shock_position_half_width(s, r), 1.5 * std::tan(0.5 * scene::kDeg), 1e-14);

  r.shock = scene::ShockKind::detached;
  r.standoff_ci = 0.03;
  EXPECT_DOUBLE_EQ(pipeline::shock_position_half_width(s, r), 0.03);
  r.shock = scene::ShockKind::none;
  EXPECT_TRUE(std::isnan(pipeline::shock_position_half_width(s, r)));
}
