// The shock probe on a hand-built strip of cells along the stagnation line;
// no OpenFOAM needed.
#include "shock_probe.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"

namespace {

constexpr double kCell = 0.1;
// Density of the free stream (gamma p / T with p = T = 1) at Mach 4.
constexpr double kRhoInf = 1.4;
constexpr double kMach = 4.0;

// Two rows of square cells of side kCell from x = -2 to the disc's nose at
// x = -0.5: one on the symmetry line (y in [0, kCell]), one above it.
cfd::Mesh2D strip() {
  cfd::Mesh2D m;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 15; ++i) {
      const double x0 = -2.0 + i * kCell, y0 = row * kCell;
      m.cell_polygons.push_back(
          {{x0, y0}, {x0 + kCell, y0}, {x0 + kCell, y0 + kCell}, {x0, y0 + kCell}});
      m.cell_area.push_back(kCell * kCell);
      m.cell_centre.push_back({x0 + 0.5 * kCell, y0 + 0.5 * kCell});
    }
  return m;
}

scene::Scene disc() {
  return scene::parse_scene("name: d\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
}

}  // namespace

TEST(ShockProbe, FindsTheRiseThroughTheMidpointBetweenCells) {
  const auto probe = cfd::ShockProbe::for_scene(disc(), {strip()});
  ASSERT_TRUE(probe.has_value());
  EXPECT_EQ(probe->samples(), 15u);  // the row on the line, not the one above
  const double rho2 = kRhoInf * scene::oblique_density_ratio(kMach, 0.5 * M_PI, 1.4);
  EXPECT_NEAR(probe->threshold(), 0.5 * (kRhoInf + rho2), 1e-12);
  // Free stream up to the cell centred at -1.05, the normal-shock state from
  // -0.95 on (the row above holds the normal-shock state everywhere, and must
  // not be read): the midpoint lies halfway, at -1.0.
  std::vector<double> rho(30, rho2);
  for (int i = 0; i < 10; ++i) rho[static_cast<std::size_t>(i)] = kRhoInf;
  const cfd::ShockReading r = probe->measure(rho);
  EXPECT_NEAR(r.x, -1.0, 1e-12);
  EXPECT_NEAR(r.cell, kCell, 1e-12);
  // A quarter of the way: the rise through the midpoint moves with it.
  rho[10] = kRhoInf + 0.75 * (rho2 - kRhoInf);
  EXPECT_NEAR(probe->measure(rho).x, -0.95 - kCell / 3.0, 1e-12);
}

TEST(ShockProbe, ReadsTheProcessorPartsOfADecomposedCase) {
  // The strip's cells dealt alternately to two parts, as processor0 and
  // processor1: the line's cells lie in both, and the reading from their
  // concatenated fields is the whole strip's.
  const cfd::Mesh2D whole = strip();
  cfd::Mesh2D parts[2];
  std::vector<std::size_t> order[2];
  for (std::size_t c = 0; c < whole.cells(); ++c) {
    cfd::Mesh2D& part = parts[c % 2];
    part.cell_polygons.push_back(whole.cell_polygons[c]);
    part.cell_area.push_back(whole.cell_area[c]);
    part.cell_centre.push_back(whole.cell_centre[c]);
    order[c % 2].push_back(c);
  }
  const auto probe = cfd::ShockProbe::for_scene(disc(), {parts[0], parts[1]});
  ASSERT_TRUE(probe.has_value());
  EXPECT_EQ(probe->samples(), 15u);
  const double rho2 = kRhoInf * scene::oblique_density_ratio(kMach, 0.5 * M_PI, 1.4);
  std::vector<double> rho;  // part 0's cells, then part 1's
  for (const auto& o : order)
    for (const std::size_t c : o) rho.push_back(c % 15 < 12 ? kRhoInf : rho2);
  EXPECT_NEAR(probe->measure(rho).x, -0.8, 1e-12);
}

TEST(ShockProbe, NoRiseIsNotMeasured) {
  const auto probe = cfd::ShockProbe::for_scene(disc(), {strip()});
  ASSERT_TRUE(probe.has_value());
  EXPECT_TRUE(std::isnan(probe->measure(std::vector<double>(30, kRhoInf)).x));
}

TEST(ShockProbe, AttachedWedgeHasNone) {
  const scene::Scene w = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n");
  EXPECT_FALSE(cfd::ShockProbe::for_scene(w, {strip()}).has_value());
}
