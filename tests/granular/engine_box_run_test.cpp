// run_box_scene: the contract's box scene, its summary keys and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "granular/box_run.hpp"
#include "granular/box_setup.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

namespace granular {
namespace {

constexpr double kRoundOffOverlap = 1e-10;
constexpr double kEnergyTolerance = 1e-10;
// A short elastic run at nu = 0.3 estimates Z to a few percent.
constexpr double kShortRunZTolerance = 0.03;

std::string out_dir(const std::string& name) {
  return test_support::absent_dir("granular_engine_" + name);
}

RunOptions opts(const std::string& name, const std::string& restart = "", std::uint64_t stop = 0) {
  RunOptions o;
  o.out_dir = out_dir(name);
  o.restart = restart;
  o.stop_after_collisions = stop;
  return o;
}

TEST(EngineBoxRun, ContractSceneWritesSummary) {
  const scene::Scene s = scene::parse_scene(R"(
box: {width: 100, height: 100, periodic: true}
granular:
  particles: 3820
  restitution: 1.0
  seed: 1
  collisions: 2.0e5
)");
  const RunOptions o = opts("contract");
  const std::string dir = o.out_dir;
  const nlohmann::json j = run_box_scene(s, o);
  ASSERT_TRUE(std::filesystem::exists(dir + "/summary.json"));
  const auto disk = nlohmann::json::parse(scene::read_file(dir + "/summary.json"));
  for (const char* key : {"particles", "collisions", "wall_seconds", "collisions_per_second", "energy_initial",
                          "energy_final", "max_overlap", "packing_fraction", "compressibility_factor",
                          "temperature"})
    EXPECT_TRUE(disk.contains(key)) << key;
  EXPECT_EQ(disk["particles"].get<int>(), 3820);
  EXPECT_EQ(disk["collisions"].get<double>(), 2.0e5);
  EXPECT_NEAR(disk["packing_fraction"].get<double>(), 0.3, 1e-4);
  EXPECT_NEAR(disk["energy_final"].get<double>() / disk["energy_initial"].get<double>(), 1.0, kEnergyTolerance);
  EXPECT_NEAR(disk["temperature"].get<double>(), 1.0, kEnergyTolerance);
  EXPECT_LE(disk["max_overlap"].get<double>(), kRoundOffOverlap);
  EXPECT_NEAR(disk["compressibility_factor"].get<double>() / ((1 + 0.09 / 8) / 0.49), 1.0, kShortRunZTolerance);
  EXPECT_EQ(j, disk);
}

TEST(EngineBoxRun, WalledInelasticBoxByTime) {
  const scene::Scene s = scene::parse_scene(R"(
box: {width: 30, height: 30, periodic: false}
granular: {packing_fraction: 0.2, restitution: 0.8, tc: 1.0e-4, time: 5.0}
)");
  const nlohmann::json j = run_box_scene(s, opts("walled"));
  EXPECT_NEAR(j["time"].get<double>(), 5.0, 1e-12);
  EXPECT_LT(j["energy_final"].get<double>(), j["energy_initial"].get<double>());
  EXPECT_GT(j["wall_collisions"].get<double>(), 0.0);
  EXPECT_LE(j["max_overlap"].get<double>(), kRoundOffOverlap);
}

TEST(EngineBoxRun, StoppedRunRestartsFromCheckpointBitIdentically) {
  const scene::Scene s = scene::parse_scene(R"(
box: {width: 40, height: 40, periodic: true}
granular: {packing_fraction: 0.35, restitution: 0.95, tc: 1.0e-4, seed: 4, collisions: 2.0e5,
           checkpoint_interval: 5.0e4}
)");
  const nlohmann::json whole = run_box_scene(s, opts("ck_whole"));
  const RunOptions stop = opts("ck_stop", "", 130000);
  const nlohmann::json part = run_box_scene(s, stop);
  EXPECT_TRUE(part["interrupted"].get<bool>());
  EXPECT_EQ(part["collisions"].get<double>(), 130000.0);
  const nlohmann::json rest = run_box_scene(s, opts("ck_rest", stop.out_dir + "/checkpoint.bin"));
  EXPECT_FALSE(rest["interrupted"].get<bool>());
  for (const char* key : {"collisions", "time", "energy_initial", "energy_final", "max_overlap",
                          "compressibility_factor", "mean_temperature", "momentum"})
    EXPECT_EQ(rest[key], whole[key]) << key;
}

// The scene parser checks these too; resolve_box repeats the checks for
// scenes built in code.
scene::Scene box_scene(std::optional<std::int64_t> particles, std::optional<double> nu) {
  scene::Scene s;
  s.source_file = "box.yaml";
  s.box = scene::Box{100, 100, true};
  s.granular.particles = particles;
  s.granular.packing_fraction = nu;
  return s;
}

TEST(EngineBoxRun, ParticlesAndPackingFractionMustAgree) {
  try {
    resolve_box(box_scene(3000, 0.3));
    FAIL() << "accepted";
  } catch (const scene::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "box.yaml: granular: particles (3000) and packing_fraction (0.3) disagree: that packing "
                 "fraction means 3820 particles in this box");
  }
  EXPECT_EQ(resolve_box(box_scene(3820, 0.3)).particles, 3820);
  EXPECT_EQ(resolve_box(box_scene(std::nullopt, 0.3)).particles, 3820);
}

TEST(EngineBoxRun, NeedsACount) {
  try {
    resolve_box(box_scene(std::nullopt, std::nullopt));
    FAIL() << "accepted";
  } catch (const scene::InputError& e) {
    EXPECT_STREQ(e.what(), "box.yaml: granular: a box scene needs particles or packing_fraction");
  }
}

TEST(EngineBoxRun, TooDenseForLatticeStart) {
  const scene::Scene s = scene::parse_scene("box: {width: 10, height: 10}\ngranular: {packing_fraction: 0.8}\n");
  try {
    make_box_engine(resolve_box(s));
    FAIL() << "accepted";
  } catch (const scene::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "granular: box: packing fraction 0.801106 is too high for the lattice start (a square "
                 "lattice of 11 x 10 sites in this box is closer than a diameter)");
  }
}

}  // namespace
}  // namespace granular
