// Hard cases on small bodies: each finishes, with no overlaps,
// and still shows the physics it is about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "flow_support.hpp"
#include "granular/flow_run.hpp"
#include "granular/flow_setup.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"

namespace {

constexpr double kOverlapTol = 1e-9;
constexpr double kMinCompression = 1.5;

granular::FlowResult run(const std::string& text) {
  const scene::Scene s = scene::parse_scene(text, "hard.yaml");
  granular::RunOptions o;
  o.np = 2;
  return granular::run_flow_scene(s, o);
}

void expect_clean(const granular::FlowResult& r) {
  EXPECT_LT(r.summary["max_overlap"].get<double>(), kOverlapTol);
  EXPECT_EQ(r.summary["recoveries"].get<double>(), 0.0);
  EXPECT_FALSE(r.summary["interrupted"].get<bool>());
}

}  // namespace

TEST(FlowHardCases, MachTenStream) {
  const granular::FlowResult r = run(R"(
body: {kind: wedge, angle_deg: 15, length: 1.0}
freestream: {mach: 3.0}
granular: {mach: 10, inflow_packing_fraction: 0.05, body_diameters: 30, lattice_nx: 30, lattice_ny: 30, warmup: 1.0, averaging: 1.0}
)");
  expect_clean(r);
  EXPECT_NEAR(r.summary["mach"].get<double>(), 10.0, 1e-12);
  EXPECT_GT(flowtest::max_of(r.fields, "volume_fraction"), kMinCompression * 0.05);
}

TEST(FlowHardCases, DenseInelasticStagnationZone) {
  // e = 0.5 in front of a disc: the stagnation zone cools and collapses into
  // a dense cluster (the TC model keeps the event rate finite).
  const granular::FlowResult r = run(R"(
body: {kind: disc, radius: 0.5}
freestream: {mach: 3.0}
granular: {restitution: 0.5, inflow_packing_fraction: 0.1, body_diameters: 12, lattice_nx: 30, lattice_ny: 30, warmup: 1.0, averaging: 1.0}
)");
  expect_clean(r);
  // Dense: far beyond the inflow packing fraction.
  EXPECT_GT(flowtest::max_of(r.fields, "volume_fraction"), 0.4);
}

TEST(FlowHardCases, GravityOn) {
  // Gravity across the stream breaks the mirror symmetry: the full body is
  // modelled, and the flow is deflected downwards.
  const granular::FlowResult r = run(R"(
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {gravity: [0, -1.0], inflow_packing_fraction: 0.05, body_diameters: 30, lattice_nx: 30, lattice_ny: 30, warmup: 1.0, averaging: 1.0}
)");
  expect_clean(r);
  EXPECT_LT(r.fields.y0, 0.0);  // full domain, not the upper half
  // Free fall from the inflow at x = -0.2 (-6 d): upstream of x = -0.05
  // (-1.5 d) a disk has fallen for ~0.5 time units on average at U ~ 4.7, so
  // v ~ -0.5 (statistical error ~0.03).
  EXPECT_LT(flowtest::upstream_mean(r.fields, "v", -0.05), -0.25);
}

TEST(FlowHardCases, ConcavePolygonWithReentrantCorner) {
  // A notch facing the stream: two faces meet at a 90 degree re-entrant
  // corner at (0.5, 0) that traps disks.
  const granular::FlowResult r = run(R"(
body: {kind: polygon, points: [[0, 0.5], [0.5, 0], [0, -0.5], [1, -0.5], [1, 0.5]]}
freestream: {mach: 3.0}
granular: {inflow_packing_fraction: 0.05, body_diameters: 20, lattice_nx: 30, lattice_ny: 30, warmup: 1.0, averaging: 1.0}
)");
  expect_clean(r);
  // The notch (x < 0.5 - |y|) fills with compressed gas.
  const scene::Lattice& lat = r.fields;
  double densest = 0;
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i)
      if (lat.xc(i) > 0.0 && lat.xc(i) < 0.5 - std::abs(lat.yc(j))) {
        const double nu = lat.field("volume_fraction")[lat.index(i, j)];
        if (std::isfinite(nu)) densest = std::max(densest, nu);
      }
  EXPECT_GT(densest, kMinCompression * 0.05);
}

TEST(FlowHardCases, BodyTouchingTheDomainEdgeIsAClearError) {
  const std::string text = R"(
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
domain: {xmin: 0.0, xmax: 1.0, ymin: 0, ymax: 0.8, symmetric: true}
)";
  try {
    (void)run(text);
    FAIL() << "expected an InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hard.yaml: domain: the body touches or crosses the inflow boundary x = xmin"),
              std::string::npos)
        << e.what();
  }
}
