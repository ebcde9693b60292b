// Field averaging: known synthetic snapshots give known fields.
#include "granular/flow_fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "granular/flow_setup.hpp"
#include "scene/scene.hpp"
#include "snapshot_binning.hpp"

namespace {

constexpr double kTight = 1e-9;
// Poisson/Gaussian sampling: relative error ~ 1/sqrt(samples per cell).
constexpr double kStatTol = 0.05;

granular::FlowSetup disc_setup() {
  const char* text = R"(
body: {kind: disc, radius: 0.5}
freestream: {mach: 3.0}
granular: {body_diameters: 20}
)";
  return granular::make_flow_setup(scene::parse_scene(text));
}

}  // namespace

TEST(FlowFields, BinnerMapsEngineToSceneCells) {
  const granular::FlowSetup f = disc_setup();
  const scene::Lattice g = granular::flow_lattice(f, 10, 8);
  const granular::Binner b(f, g);
  const scene::Vec2 centre{g.xc(3), g.yc(5)};
  EXPECT_EQ(b.cell_of(granular::to_engine(f, centre)), g.index(3, 5));
  EXPECT_EQ(b.cell_of(granular::to_engine(f, {f.domain.xmin - 0.01, 0.0})), granular::Binner::npos);
  EXPECT_EQ(b.cell_of(granular::to_engine(f, {f.domain.xmax, f.domain.ymax})), g.index(9, 7));
}

// The look-ahead binning adds in the disks' order, so its sums are a plain
// loop's to the last bit, for snapshots shorter and longer than the look-ahead,
// with disks outside the lattice among them, and it counts every disk.
TEST(FlowFields, SnapshotBinningMatchesAPlainLoopBitForBit) {
  const granular::FlowSetup f = disc_setup();
  const scene::Lattice g = granular::flow_lattice(f, 30, 20);
  const granular::Binner binner(f, g);
  const std::size_t cells = static_cast<std::size_t>(g.nx * g.ny);
  std::mt19937_64 rng(11);
  // A quarter of the disks fall outside the lattice (the simulated domain
  // of a disc is larger than the scene's).
  const scene::Domain& d = f.domain;
  const double pad = 0.25 * d.width();
  std::uniform_real_distribution<double> ux((d.xmin - pad) * f.scale, d.xmax * f.scale),
      uy(d.ymin * f.scale, d.ymax * f.scale), uv(-3.0, 7.0);
  for (const std::size_t count :
       {std::size_t{0}, std::size_t{1}, granular::kBinLookahead - 1, granular::kBinLookahead,
        granular::kBinLookahead + 1, std::size_t{5000}}) {
    std::vector<std::pair<scene::Vec2, scene::Vec2>> disks;
    for (std::size_t k = 0; k < count; ++k)
      disks.push_back({{ux(rng), uy(rng)}, {uv(rng), uv(rng)}});
    granular::FieldSums plain(cells), ahead(cells);
    for (const auto& [r, v] : disks)
      if (const std::size_t c = binner.cell_of(r); c != granular::Binner::npos) plain.add(c, v);
    plain.end_snapshot();
    const std::size_t seen = granular::bin_snapshot(binner, ahead, [&](const auto& add) {
      for (const auto& [r, v] : disks) add(r, v);
    });
    EXPECT_EQ(seen, count);
    EXPECT_EQ(ahead.raw(), plain.raw()) << count << " disks";
  }
}

TEST(FlowFields, UniformGasGivesItsStateAndBodyCellsAreMarked) {
  const granular::FlowSetup f = disc_setup();
  const scene::Lattice g = granular::flow_lattice(f, 12, 12);
  const granular::Binner binner(f, g);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  // Disks over the lattice's domain (the simulated one is larger for a disc).
  const scene::Domain& d = f.domain;
  std::uniform_real_distribution<double> ux(d.xmin * f.scale, d.xmax * f.scale), uy(d.ymin * f.scale, d.ymax * f.scale);
  const double n = 0.05 / (std::numbers::pi / 4);
  const auto per_snap = static_cast<int>(n * d.width() * d.height() * f.scale * f.scale);
  std::vector<granular::FieldSums> blocks(2, granular::FieldSums(144));
  const double big_u = 4.0, temp = 2.0;
  for (auto& blk : blocks)
    for (int s = 0; s < 300; ++s) {
      for (int k = 0; k < per_snap; ++k) {
        const scene::Vec2 r{ux(rng), uy(rng)};
        // Centres stay a radius off the wall (as the fields assume).
        if (scene::signed_distance(f.body, granular::to_scene(f, r)) < 0.5 / f.scale) continue;
        const std::size_t cell = binner.cell_of(r);
        ASSERT_NE(cell, granular::Binner::npos);
        blk.add(cell, {big_u + std::sqrt(temp) * gauss(rng), std::sqrt(temp) * gauss(rng)});
      }
      blk.end_snapshot();
    }
  const scene::Lattice lat = granular::make_fields(f, g, blocks);
  for (const char* name : {"volume_fraction", "number_density", "u", "v", "temperature", "pressure", "mach",
                           "samples", "inside_body", "volume_fraction_se", "u_se", "v_se"})
    EXPECT_TRUE(lat.has(name)) << name;
  // A far-field cell (corner) and the centre (inside the disc).
  // The disc is centred at the origin on the symmetry plane y = 0.
  const auto ic = static_cast<int>((0.0 - lat.x0) / lat.dx);
  const std::size_t far = lat.index(0, 11), centre = lat.index(ic, 0);
  EXPECT_EQ(lat.field("inside_body")[centre], 1.0);
  EXPECT_TRUE(std::isnan(lat.field("volume_fraction")[centre]));
  EXPECT_EQ(lat.field("inside_body")[far], 0.0);
  EXPECT_NEAR(lat.field("volume_fraction")[far], 0.05, kStatTol * 0.05 * 2);
  EXPECT_NEAR(lat.field("u")[far], big_u, kStatTol * big_u);
  EXPECT_NEAR(lat.field("temperature")[far], temp, kStatTol * temp * 2);
  EXPECT_NEAR(lat.field("mach")[far], std::hypot(lat.field("u")[far], lat.field("v")[far]) / granular::sound_speed(lat.field("volume_fraction")[far],
                                                                     lat.field("temperature")[far]), kTight);
  const double se = lat.field("volume_fraction_se")[far];
  EXPECT_TRUE(std::isfinite(se));
  EXPECT_LT(se, 0.01);
  // Cells cut by the disc divide by their fluid area only, so the density
  // near the wall is still the free-stream one (no dip from the body's area).
  int cut_cells = 0;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i) {
      const std::size_t c = lat.index(i, j);
      if (lat.field("inside_body")[c] == 0.0 && scene::signed_distance(f.body, {lat.xc(i), lat.yc(j)}) < 0.5 * lat.dx) {
        ++cut_cells;
        EXPECT_NEAR(lat.field("volume_fraction")[c], 0.05, 0.3 * 0.05) << i << "," << j;
      }
    }
  EXPECT_GT(cut_cells, 0);
}
