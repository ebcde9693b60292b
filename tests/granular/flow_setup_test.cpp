// Flow setup: sound speed, Mach number, scale and walls from a scene.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "granular/flow_fields.hpp"
#include "granular/flow_replica.hpp"
#include "granular/flow_setup.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace {

constexpr double kTight = 1e-12;
using scene::kDeg;
// Henderson's Z reproduces the exact hard-disk virial series
// Z = 1 + 2 nu + 3.1280 nu^2 + O(nu^3) (B3 of hard disks, 3.1280 in these
// units): at nu = 0.01 the remainder is ~4 nu^3.
constexpr double kVirialTol = 1e-5;
// The fluid area is measured on a 256^2 sub-lattice: ~0.5% of the body area.
constexpr double kAreaTol = 0.005;

const char* kWedge = R"(
name: w
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {inflow_packing_fraction: 0.05, body_diameters: 50}
)";

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(FlowSetup, SoundSpeedDiluteLimitIsGammaTwo) {
  // c^2 = 2 T / m for the dilute 2D hard-disk gas.
  EXPECT_NEAR(granular::sound_speed(0.0, 1.0), std::sqrt(2.0), kTight);
  EXPECT_NEAR(granular::sound_speed(0.0, 4.0), 2.0 * std::sqrt(2.0), kTight);
  // Dense: faster than dilute, and increasing with density.
  EXPECT_GT(granular::sound_speed(0.1, 1.0), granular::sound_speed(0.05, 1.0));
  const double nu = 0.01;
  EXPECT_NEAR(granular::henderson_z(nu), 1 + 2 * nu + 3.1280 * nu * nu, kVirialTol);
}

TEST(FlowSetup, SoundSpeedMatchesNumericalDerivative) {
  // c^2 = (dp/drho)_s with p = n T Z(n), e = T per disk: check against a
  // finite-difference isentrope (dT/dn = p / n^2 at constant entropy).
  const double nu = 0.2, t = 1.3, k = std::numbers::pi / 4, h = 1e-6;
  const double n = nu / k;
  auto p = [&](double nn, double tt) { return nn * tt * granular::henderson_z(nn * k); };
  const double dtdn = p(n, t) / (n * n);
  const double c2 = (p(n + h, t + dtdn * h) - p(n - h, t - dtdn * h)) / (2 * h);
  EXPECT_NEAR(granular::sound_speed(nu, t), std::sqrt(c2), 1e-6);
}

TEST(FlowSetup, WedgeScaleWallsAndInflow) {
  const scene::Scene s = scene::parse_scene(kWedge);
  const granular::FlowSetup f = granular::make_flow_setup(s);
  EXPECT_NEAR(f.scale, 50.0, kTight);
  EXPECT_TRUE(f.config.symmetric);
  EXPECT_NEAR(f.config.inflow_speed, 3.0 * granular::sound_speed(0.05, 1.0), kTight);
  ASSERT_EQ(f.config.body_chains.size(), 1u);
  const auto& chain = f.config.body_chains[0];
  ASSERT_EQ(chain.size(), 2u);  // apex to the outflow cut
  EXPECT_NEAR(chain[0].x, 0.0, kTight);
  EXPECT_NEAR(chain[1].x, 50 * std::cos(10 * kDeg), 1e-9);
  EXPECT_NEAR(chain[1].y, 50 * std::sin(10 * kDeg), 1e-9);
  EXPECT_NEAR(f.config.xmax, 50 * s.body->length * std::cos(10 * kDeg), 1e-9);
  // Fluid area = domain minus the wedge's upper half (a triangle).
  const double tri = 0.5 * 50 * std::cos(10 * kDeg) * 50 * std::sin(10 * kDeg);
  const double box = (f.config.xmax - f.config.xmin) * (f.config.ymax - f.config.ymin);
  EXPECT_NEAR(f.fluid_area, box - tri, kAreaTol * box);
}

TEST(FlowSetup, GranularMachOverridesFreestream) {
  scene::Scene s = scene::parse_scene(kWedge);
  EXPECT_NEAR(granular::make_flow_setup(s).mach, 3.0, kTight);
  s.granular.mach = 10.0;
  EXPECT_NEAR(granular::make_flow_setup(s).mach, 10.0, kTight);
}

TEST(FlowSetup, ParticlesFixTheScale) {
  scene::Scene s = scene::parse_scene(kWedge);
  s.granular.body_diameters.reset();
  s.granular.particles = 2000;
  EXPECT_NEAR(granular::make_flow_setup(s).expected_particles, 2000.0, 1e-6);
  // Neither given: the default count; the wedge M3/10 body is then ~300 d.
  s.granular.particles.reset();
  s.granular.inflow_packing_fraction = 0.1;
  const granular::FlowSetup f = granular::make_flow_setup(s);
  EXPECT_NEAR(f.expected_particles, scene::kDefaultFlowParticles, 1e-6);
  EXPECT_NEAR(f.body.length * f.scale, 300.0, 3.0);
}

TEST(FlowSetup, BodyTouchingTheDomainEdgeIsAClearError) {
  const char* text = R"(
body: {kind: disc, radius: 0.5}
freestream: {mach: 3.0}
domain: {xmin: -2, xmax: 1, ymin: -0.5, ymax: 2}
)";
  const std::string msg = error_of([&] { (void)granular::make_flow_setup(scene::parse_scene(text, "touch.yaml")); });
  EXPECT_NE(msg.find("touch.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("touches or crosses the side boundary y = ymin"), std::string::npos) << msg;
}

TEST(FlowSetup, SubsonicGranularMachIsRejected) {
  scene::Scene s = scene::parse_scene(kWedge, "sub.yaml");
  s.granular.mach = 0.8;
  const std::string msg = error_of([&] { (void)granular::make_flow_setup(s); });
  EXPECT_NE(msg.find("sub.yaml: granular: key 'mach'"), std::string::npos) << msg;
}

TEST(FlowSetup, SteadyTestOnCounts) {
  std::vector<double> rising, flat;
  for (int k = 0; k < 40; ++k) {
    rising.push_back(1000.0 + 20.0 * k);
    flat.push_back(1000.0 + ((k % 2) ? 5.0 : -5.0));
  }
  EXPECT_FALSE(granular::counts_steady(rising, 10));
  EXPECT_TRUE(granular::counts_steady(flat, 10));
  EXPECT_FALSE(granular::counts_steady(std::vector<double>(15, 1000.0), 10));  // too short
}

TEST(FlowSetup, WallsOfANotchFacingTheStream) {
  // The most upstream points (0, +-0.5) are off the symmetry line; the
  // upper-half wall must still run from the re-entrant corner on the axis.
  const char* text = R"(
body: {kind: polygon, points: [[0, 0.5], [0.5, 0], [0, -0.5], [1, -0.5], [1, 0.5]]}
freestream: {mach: 3.0}
)";
  const granular::FlowSetup f = granular::make_flow_setup(scene::parse_scene(text));
  const auto chains = granular::body_chains(f.body, f.domain);
  ASSERT_EQ(chains.size(), 1u);
  ASSERT_EQ(chains[0].size(), 3u);
  EXPECT_EQ(chains[0][0], (scene::Vec2{0.5, 0.0}));
  EXPECT_EQ(chains[0][1], (scene::Vec2{0.0, 0.5}));
  EXPECT_EQ(chains[0][2], (scene::Vec2{1.0, 0.5}));
}

TEST(FlowSetup, WallsOfABodyWhollyInsideAreAClosedLoop) {
  const char* text = R"(
body: {kind: polygon, points: [[0, 0], [1, 0.2], [0.2, 1]]}
freestream: {mach: 3.0}
domain: {xmin: -1, xmax: 2, ymin: -1, ymax: 2}
)";
  const granular::FlowSetup f = granular::make_flow_setup(scene::parse_scene(text));
  ASSERT_EQ(f.config.body_chains.size(), 1u);
  const auto& loop = f.config.body_chains[0];
  ASSERT_EQ(loop.size(), 4u);
  EXPECT_EQ(loop.front(), loop.back());
  // Body on the right: clockwise, so the signed area is negative.
  double area2 = 0;
  for (std::size_t k = 0; k + 1 < loop.size(); ++k) area2 += cross(loop[k], loop[k + 1]);
  EXPECT_LT(area2, 0.0);
}
