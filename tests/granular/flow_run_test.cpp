// End to end through the library on a small wedge: files, keys, free-stream
// state recovered, compression at the body, no overlaps, reproducibility.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "flow_support.hpp"
#include "granular/flow_run.hpp"
#include "granular/flow_setup.hpp"
#include "scene/cli.hpp"
#include "scene/scene.hpp"

namespace {

// Overlaps are repaired only beyond round-off; a clean run has none deeper
// than this (diameters).
constexpr double kOverlapTol = 1e-9;
// Free-stream statistics of a short small run: ~10% on density and
// temperature, a few % on the mean speed.
constexpr double kDensityTol = 0.12;
constexpr double kSpeedTol = 0.04;
constexpr double kTemperatureTol = 0.15;
// The oblique shock compresses the stream at least this much at the wedge.
constexpr double kMinCompression = 1.5;

const char* kSmallWedge = R"(
name: small_wedge
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {inflow_packing_fraction: 0.05, body_diameters: 40, lattice_nx: 40, lattice_ny: 30, warmup: 1.0, averaging: 1.5, replicas: 2, seed: 11}
)";

}  // namespace

TEST(FlowRun, SmallWedgeWritesFieldsAndSummary) {
  const std::string dir = flowtest::temp_dir("small_wedge");
  const scene::Scene s = scene::parse_scene(kSmallWedge);
  granular::RunOptions o;
  o.out_dir = dir;
  o.np = 2;
  const granular::FlowResult r = granular::run_flow_scene(s, o);
  ASSERT_TRUE(std::filesystem::exists(dir + "/fields.vti"));
  ASSERT_TRUE(std::filesystem::exists(dir + "/summary.json"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
  for (const char* k : {"particles", "collisions", "wall_seconds", "collisions_per_second", "energy_initial",
                        "energy_final", "max_overlap", "packing_fraction", "replicas", "mach", "inflow_speed",
                        "warmup_time", "steady_detected"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["replicas"], 2);
  EXPECT_GT(j["collisions"].get<double>(), 0);
  EXPECT_LT(j["max_overlap"].get<double>(), kOverlapTol);
  EXPECT_EQ(j["recoveries"].get<double>(), 0.0);

  const scene::Lattice lat = scene::read_vti(dir + "/fields.vti");
  EXPECT_EQ(lat.nx, 40);
  EXPECT_EQ(lat.ny, 30);
  const scene::Domain d = scene::scene_domain(s);
  EXPECT_NEAR(lat.x0, d.xmin, 1e-12);
  // Upstream of the apex the stream is undisturbed.
  const double u_inf = 3.0 * granular::sound_speed(0.05, 1.0);
  EXPECT_NEAR(flowtest::upstream_mean(lat, "volume_fraction", -0.05), 0.05, kDensityTol * 0.05);
  EXPECT_NEAR(flowtest::upstream_mean(lat, "u", -0.05), u_inf, kSpeedTol * u_inf);
  EXPECT_NEAR(flowtest::upstream_mean(lat, "temperature", -0.05), 1.0, kTemperatureTol);
  // Mach number of the mean upstream state (the per-cell Mach of a few
  // samples is biased: it divides by a noisy sound speed).
  const double nu_up = flowtest::upstream_mean(lat, "volume_fraction", -0.05);
  const double mach_up = flowtest::upstream_mean(lat, "u", -0.05) /
                         granular::sound_speed(nu_up, flowtest::upstream_mean(lat, "temperature", -0.05));
  EXPECT_NEAR(mach_up, 3.0, 3.0 * (kSpeedTol + kTemperatureTol / 2));
  EXPECT_GT(flowtest::max_of(lat, "volume_fraction"), kMinCompression * 0.05);
  // Two replicas: the per-cell spread exists in the free stream.
  EXPECT_TRUE(std::isfinite(flowtest::upstream_mean(lat, "volume_fraction_se", -0.05)));
  // The averaging groups (the shock's interval): four per replica, written
  // beside the fields; each group's disks add up to the pooled count and its
  // volume fraction is the pooled one scaled by its share of the snapshots.
  ASSERT_EQ(r.groups.size(), 8u);
  ASSERT_TRUE(std::filesystem::exists(dir + "/groups.vti"));
  const std::size_t up = lat.index(2, lat.ny / 2);
  double nu_weighted = 0.0, samples = 0.0;
  for (const scene::Lattice& g : r.groups) {
    EXPECT_EQ(g.field("samples")[up],
              lat.field("samples")[up]);  // the pooled count, for the sample gate
    nu_weighted += g.field("volume_fraction")[up];
    samples += 1.0;
  }
  // Equal slices: the groups' mean volume fraction is the pooled one within
  // the share of snapshots their slices differ by (one slice in eight).
  constexpr double kSliceShareTol = 0.15;
  EXPECT_NEAR(nu_weighted / samples, lat.field("volume_fraction")[up],
              kSliceShareTol * lat.field("volume_fraction")[up]);
  // The apex region is body: marked, NaN.
  const std::size_t c = lat.index(lat.nx - 1, 0);
  EXPECT_EQ(lat.field("inside_body")[c], 1.0);
  EXPECT_TRUE(std::isnan(lat.field("u")[c]));
  EXPECT_EQ(r.fields.nx, 40);
}

TEST(FlowRun, ThreadsDoNotChangeTheResult) {
  // Replicas are independent and reduced in a fixed order: one thread or
  // two give bit-identical fields.
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.averaging = 0.5;
  s.granular.warmup = 0.5;
  granular::RunOptions o1, o2;
  o1.np = 1;
  o2.np = 2;
  const granular::FlowResult a = granular::run_flow_scene(s, o1);
  const granular::FlowResult b = granular::run_flow_scene(s, o2);
  const auto& fa = a.fields.field("volume_fraction");
  const auto& fb = b.fields.field("volume_fraction");
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t k = 0; k < fa.size(); ++k)
    if (!std::isnan(fa[k])) {
      ASSERT_EQ(fa[k], fb[k]) << k;
    }
  EXPECT_EQ(a.summary["collisions"], b.summary["collisions"]);
}

TEST(FlowRun, SingleReplicaUsesBatchesForTheSpread) {
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.replicas = 1;
  s.granular.averaging = 1.0;
  s.granular.warmup = 0.5;
  const granular::FlowResult r = granular::run_flow_scene(s, granular::RunOptions{});
  EXPECT_TRUE(std::isfinite(flowtest::upstream_mean(r.fields, "volume_fraction_se", -0.05)));
}

TEST(FlowRun, WarmupDetectsSteadyState) {
  scene::Scene s = scene::parse_scene(kSmallWedge);
  s.granular.warmup.reset();
  s.granular.replicas = 1;
  s.granular.averaging = 0.5;
  const granular::FlowResult r = granular::run_flow_scene(s, granular::RunOptions{});
  EXPECT_TRUE(r.summary["steady_detected"].get<bool>());
  EXPECT_GE(r.summary["warmup_flow_throughs"].get<double>(), 1.0 - 1e-9);
  EXPECT_LT(r.summary["warmup_flow_throughs"].get<double>(), 8.0);
}

TEST(FlowRun, EveryShippedCaseRunsShortened) {
  // Every body scene shipped in pipeline/cases runs (small and short here):
  // no overlaps, and a shock compresses the stream somewhere.
  for (const char* name : {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"}) {
    scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    s.granular.particles = 1500;
    s.granular.lattice_nx = 40;
    s.granular.lattice_ny = 40;
    s.granular.warmup = 1.0;
    s.granular.averaging = 0.5;
    s.granular.replicas = 1;
    granular::RunOptions o;
    o.np = 1;
    const granular::FlowResult r = granular::run_flow_scene(s, o);
    EXPECT_LT(r.summary["max_overlap"].get<double>(), kOverlapTol) << name;
    EXPECT_EQ(r.summary["recoveries"].get<double>(), 0.0) << name;
    const double nu_inf = r.summary["packing_fraction"].get<double>();
    EXPECT_GT(flowtest::max_of(r.fields, "volume_fraction"), kMinCompression * nu_inf) << name;
  }
}

// The inelastic free stream cools as it flows, so its Mach number rises
// downstream (a small wedge M4.5/12 at e = 0.95: about 4.7 at the inlet,
// 6.2 at the outlet); elastic impacts below 4 inflow thermal speeds keep it
// at the scene's Mach number (4.53-4.61), while the shock still forms.
TEST(FlowRun, ElasticSlowImpactsKeepTheFreeStreamAtItsMachNumber) {
  // Top rows, above the shock: the free stream, in blocks of columns.
  constexpr int kTopRows = 6, kBlock = 5;
  const auto top_mach = [](const scene::Lattice& lat, int i0) {
    const auto& m = lat.field("mach");
    double s = 0;
    int k = 0;
    for (int j = lat.ny - kTopRows; j < lat.ny; ++j)
      for (int i = i0; i < i0 + kBlock; ++i)
        if (std::isfinite(m[lat.index(i, j)])) {
          s += m[lat.index(i, j)];
          ++k;
        }
    return s / k;
  };
  const auto run = [](double elastic) {
    const std::string text =
        "name: cooling\nbody: {kind: wedge, angle_deg: 12, length: 1.0}\nfreestream: {mach: 4.5}\n"
        "granular: {restitution: 0.95, body_diameters: 200, lattice_nx: 40, lattice_ny: 30, "
        "warmup: 1.0, averaging: 2, replicas: 2, seed: 11, elastic_impact_speed: " +
        std::to_string(elastic) + "}\n";
    granular::RunOptions o;
    o.np = 2;
    return granular::run_flow_scene(scene::parse_scene(text), o).fields;
  };
  const scene::Lattice cooling = run(0.0), kept = run(4.0);
  const int last = cooling.nx - kBlock;
  // Statistics of a short run: a few % per block.
  constexpr double kMachTol = 0.05;
  constexpr double kMinRise = 1.15;
  EXPECT_GT(top_mach(cooling, last) / top_mach(cooling, 0), kMinRise);
  EXPECT_NEAR(top_mach(kept, 0) / 4.5, 1.0, kMachTol);
  EXPECT_NEAR(top_mach(kept, last) / 4.5, 1.0, kMachTol);
  // Still a shock: the stream is compressed at the wedge.
  EXPECT_GT(flowtest::max_of(kept, "volume_fraction"),
            kMinCompression * flowtest::upstream_mean(kept, "volume_fraction", 0.0));
}
