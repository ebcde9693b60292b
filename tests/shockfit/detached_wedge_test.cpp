// Wedges just beyond their maximum deflection: the granular bow shock ahead
// of a sharp apex is about as thick as its standoff, so the stagnation
// line's density rises smoothly to the nose and its jump alone does not pass
// the station tests. The stations standing upstream of the apex still say
// the shock stands off; before they counted, such runs were fitted as an
// attached line at ~58 deg crossing the axis ~0.4 body lengths ahead of the
// apex. Real granular runs at the default scale, fixed seeds. Slow: a few
// CPU seconds each.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "granular/flow_run.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"
#include "shockfit/locate.hpp"

namespace {

namespace fs = std::filesystem;

// The standoff of a shock that stands off at all: beyond the attached limit
// (0.02 body lengths), and inside the upstream domain.
constexpr double kMinStandoff = 0.05;
constexpr double kMaxStandoff = 1.0;

// A unit-length wedge of `angle_deg` at `mach`, restitution `e`, seed 7.
shockfit::ShockResult locate_wedge(double mach, double angle_deg, double e) {
  const std::string text = "body: {kind: wedge, angle_deg: " + std::to_string(angle_deg) +
                           ", length: 1.0}\nfreestream: {mach: " + std::to_string(mach) +
                           "}\ngranular: {restitution: " + std::to_string(e) + ", seed: 7}\n";
  const scene::Scene s = scene::parse_scene(text, "detached_wedge.yaml");
  granular::RunOptions o;
  o.np = 2;
  o.out_dir =
      (test_support::scratch_root() / ("shockfit_detached_" + std::to_string(::getpid()))).string();
  const granular::FlowResult g = granular::run_flow_scene(s, o);
  fs::remove_all(o.out_dir);
  return shockfit::locate_shock(s, g.fields);
}

void expect_standing_off(const shockfit::ShockResult& r) {
  EXPECT_EQ(r.shock, scene::ShockKind::detached);
  EXPECT_TRUE(std::isnan(r.shock_angle_deg));
  EXPECT_GT(r.standoff, kMinStandoff);
  EXPECT_LT(r.standoff, kMaxStandoff);
  EXPECT_GT(r.standoff_ci, 0.0);
}

}  // namespace

// theta_max(M 2.5) = 29.8 deg.
TEST(DetachedWedge, MachTwoAndAHalfThirtyOneDegreesStandsOff) {
  expect_standing_off(locate_wedge(2.5, 31, 0.985));
}

// theta_max(M 3) = 34.1 deg.
TEST(DetachedWedge, MachThreeThirtySixDegreesStandsOff) {
  expect_standing_off(locate_wedge(3, 36, 0.98));
}
