// The precision target a scene asks for and the shock position half-width
// it is compared with (no granular run).
#include "pipeline/precision_goal.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "shockfit/group_interval.hpp"

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

TEST(PrecisionGoal, ABandTargetIsTheAngleIntervalThatWidensTheBandByAFifth) {
  // A scatter of 0.3 deg: the band's own part is 1.96 x 0.3; a run interval
  // of sqrt(1.2^2 - 1) times it makes the band 1.2 times as wide.
  constexpr double kScatterDeg = 0.3;
  const scene::Scene s = wedge("{target_half_width: band}");
  EXPECT_TRUE(scene::parse_scene(scene::to_yaml(s)).granular.target_from_band);
  const granular::PrecisionGoal g = pipeline::precision_goal(s, kScatterDeg);
  ASSERT_TRUE(g.active());
  EXPECT_EQ(g.unit, "deg");
  EXPECT_EQ(g.min_flow_throughs, pipeline::kBandMinAveraging);
  const double own = shockfit::kNormal95 * kScatterDeg;
  EXPECT_NEAR(std::hypot(g.target, own), (1.0 + pipeline::kBandWidening) * own, 1e-12);
  // Without a calibrated band there is nothing to be small against.
  EXPECT_THROW(pipeline::precision_goal(s), scene::InputError);
}

TEST(PrecisionGoal, ARunDefaultsToTheBandOnlyWhereTheSceneLeftTheAveragingOpen) {
  constexpr double kScatterDeg = 0.3;
  scene::Scene open = wedge("{}");
  EXPECT_TRUE(pipeline::default_to_band_target(open, kScatterDeg));
  EXPECT_TRUE(open.granular.target_from_band);
  for (const char* set :
       {"{averaging: 16}", "{target_half_width: 0.01}", "{target_half_width: mesh}"}) {
    scene::Scene s = wedge(set);
    EXPECT_FALSE(pipeline::default_to_band_target(s, kScatterDeg)) << set;
    EXPECT_FALSE(s.granular.target_from_band) << set;
  }
  scene::Scene uncalibrated = wedge("{}");
  EXPECT_FALSE(pipeline::default_to_band_target(uncalibrated, scene::kNaN));
  // A wedge beyond its maximum deflection has a bow shock: no angle band.
  scene::Scene detached = scene::parse_scene(
      "name: d\nbody: {kind: wedge, angle_deg: 36, length: 1.0}\nfreestream: {mach: 3}\n");
  EXPECT_FALSE(pipeline::default_to_band_target(detached, kScatterDeg));
}

TEST(PrecisionGoal, ARunKeepsTwoReplicasOnlyForABowShockWhoseBandIsTheTables) {
  // A scene default of four replicas for bow shocks; a run whose band is
  // the table's bow scatter (~+-30%) goes back to two, where the scene left
  // them open.
  constexpr double kBowRelative = 0.17;
  const char* disc = "name: c\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n";
  scene::Scene open = scene::parse_scene(disc);
  ASSERT_EQ(open.granular.replicas, scene::kBowShockReplicas);
  EXPECT_TRUE(pipeline::default_to_band_replicas(open, kBowRelative));
  EXPECT_EQ(open.granular.replicas, scene::kDefaultReplicas);
  scene::Scene given = scene::parse_scene(std::string(disc) + "granular: {replicas: 4}\n");
  EXPECT_FALSE(pipeline::default_to_band_replicas(given, kBowRelative));
  EXPECT_EQ(given.granular.replicas, 4);
  // Without the table's scatter the band is the run's own interval.
  scene::Scene own = scene::parse_scene(disc);
  EXPECT_FALSE(pipeline::default_to_band_replicas(own, scene::kNaN));
  EXPECT_EQ(own.granular.replicas, scene::kBowShockReplicas);
  // An attached shock keeps what it has (its averaging follows its band).
  scene::Scene attached = wedge("{}");
  EXPECT_FALSE(pipeline::default_to_band_replicas(attached, kBowRelative));
  EXPECT_EQ(attached.granular.replicas, scene::kDefaultReplicas);
}

TEST(PrecisionGoal, PredictAveragesABowShockToItsStandoffTarget) {
  const char* disc = "name: c\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n";
  scene::Scene open = scene::parse_scene(disc);
  EXPECT_TRUE(pipeline::default_to_standoff_target(open));
  EXPECT_TRUE(open.granular.target_from_standoff);
  EXPECT_TRUE(open.granular.asks_precision());
  // The resolved scene keeps the choice, so a rerun averages the same way.
  EXPECT_TRUE(scene::parse_scene(scene::to_yaml(open)).granular.target_from_standoff);
  const granular::PrecisionGoal g = pipeline::precision_goal(open);
  ASSERT_TRUE(g.active());
  EXPECT_EQ(g.unit, "relative");
  EXPECT_DOUBLE_EQ(g.target, pipeline::kStandoffTargetRelative);
  // Never shorter than the averaging a bow shock had without it.
  EXPECT_DOUBLE_EQ(g.min_flow_throughs, open.granular.averaging);
  // A scene that sets its averaging or a target, and an attached shock, keep theirs.
  for (const char* set : {"granular: {averaging: 6}", "granular: {target_half_width: 0.01}"}) {
    scene::Scene s = scene::parse_scene(std::string(disc) + set + "\n");
    EXPECT_FALSE(pipeline::default_to_standoff_target(s)) << set;
    EXPECT_FALSE(s.granular.target_from_standoff) << set;
  }
  scene::Scene attached = wedge("{}");
  EXPECT_FALSE(pipeline::default_to_standoff_target(attached));
  EXPECT_TRUE(scene::parse_scene(std::string(disc) + "granular: {target_half_width: standoff}\n")
                  .granular.target_from_standoff);
}

TEST(PrecisionGoal, ABandGoalPricesTheFinestClusteredGridByItsBand) {
  // The model's CPU of the finest clustered grid (h_min 0.01 body lengths
  // here): meshgen's band is at least 3 h_min either side of the shock, so an
  // angle interval that makes it no wider (up to 1 deg and beyond here) costs
  // the same as an exact angle, and a wider one costs more. An angle or width that cannot be placed
  // is not priced.
  constexpr double kScatterDeg = 0.12;
  const granular::PrecisionGoal g =
      pipeline::precision_goal(wedge("{target_half_width: band}"), kScatterDeg);
  ASSERT_TRUE(g.downstream_cpu);
  const auto cpu = [&](double hw) { return g.downstream_cpu(27.0, hw); };
  EXPECT_GT(cpu(0.0), 0.0);
  EXPECT_DOUBLE_EQ(cpu(0.5), cpu(0.0));
  EXPECT_GT(cpu(2.0), cpu(0.5));
  EXPECT_GT(cpu(4.0), cpu(2.0));
  EXPECT_TRUE(std::isnan(g.downstream_cpu(std::nan(""), 0.5)));
  EXPECT_TRUE(std::isnan(g.downstream_cpu(27.0, std::nan(""))));
  // Goals other than the band's leave the averaging unpriced.
  EXPECT_FALSE(pipeline::precision_goal(wedge("{target_half_width: mesh}")).downstream_cpu);
}
