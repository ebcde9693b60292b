// pipeline parametric: a few real granular runs (fixed seeds) whose physics
// must hold, the calibration crossing arithmetic, and bad input (exit 2).
#include "pipeline/parametric.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "scene/errors.hpp"
#include "scene/units.hpp"
#include "scratch.hpp"

namespace {

namespace fs = std::filesystem;
using scene::kDeg;

int exit_code(const std::string& args) {
  const std::string cmd = std::string(BIN_DIR) + "/pipeline " + args + " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Small, cheap points: the physics, not the precision, is under test.
pipeline::ParametricPoint small_wedge(double theta, double e) {
  pipeline::ParametricPoint p;
  p.body = "wedge";
  p.mach = p.granular_mach = 3;
  p.theta_deg = theta;
  p.restitution = e;
  return p;
}

}  // namespace

TEST(Parametric, BadInputExitsTwo) {
  const auto out = (test_support::scratch_root() / "parametric_bad").string();
  EXPECT_EQ(exit_code("parametric --out " + out + " --no-such-option"), 2);
  EXPECT_EQ(exit_code("parametric --out " + out + " --budget-cpu-seconds 0"), 2);
  EXPECT_EQ(exit_code("parametric --out " + out + " --budget-cpu-seconds -5"), 2);
  EXPECT_EQ(exit_code("parametric --out " + out + " --jobs 0"), 2);
  EXPECT_EQ(exit_code("parametric --budget-cpu-seconds 10"), 2);  // --out missing
}

TEST(Parametric, GridsKeepCaseStudiesOutOfTraining) {
  for (const auto grid : {pipeline::ParametricGrid::quick, pipeline::ParametricGrid::full})
    for (const auto& panel : pipeline::parametric_panels(grid))
      for (const auto& p : panel.points) {
        EXPECT_NO_THROW((void)pipeline::point_scene(p)) << pipeline::point_key(p);
        // Its recorded replicas, a disc's too (the cache key names none).
        EXPECT_EQ(pipeline::point_scene(p).granular.replicas, scene::kDefaultReplicas)
            << pipeline::point_key(p);
        if (p.body == "wedge" && p.mach == 3 && p.theta_deg == 10) {
          EXPECT_TRUE(pipeline::is_case_study(p));
        }
      }
  EXPECT_FALSE(pipeline::is_case_study(small_wedge(20, 1)));
}

TEST(Parametric, CrossingInterpolatesAndPropagatesIntervals) {
  // gas 30 deg; e = 0.9 gives 25 +- 1, e = 1 gives 35 +- 1: crossing at 0.95.
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [e, b] : {std::pair{0.9, 25.0}, {1.0, 35.0}})
    rows.push_back({{"body", "wedge"},
                    {"mach", 2.5},
                    {"granular_mach", 2.5},
                    {"packing", 0.1},
                    {"theta_deg", 12.0},
                    {"restitution", e},
                    {"beta_deg", b},
                    {"beta_ci_deg", 1.0},
                    {"gas_beta_deg", 30.0},
                    {"case_study", false}});
  const auto cs = pipeline::calibration_crossings(rows);
  ASSERT_EQ(cs.size(), 1u);
  ASSERT_TRUE(cs[0].found);
  EXPECT_NEAR(cs[0].restitution, 0.95, 1e-12);
  EXPECT_NEAR(cs[0].ci, 0.1 / 10 * std::hypot(0.5, 0.5), 1e-12);
}

// Real granular runs: four wedges and a disc, about a CPU minute.
TEST(Parametric, ShortStudyPhysics) {
  const auto out = (test_support::scratch_root() / "parametric_short").string();
  fs::remove_all(out);
  pipeline::ParametricPanel wedges{
      "w",
      "wedges",
      "theta_beta",
      {small_wedge(10, 1.0), small_wedge(20, 1.0), small_wedge(10, 0.9)}};
  pipeline::ParametricPoint disc;
  disc.body = "disc";
  disc.mach = disc.granular_mach = 4;
  disc.radius_d = 60;
  disc.averaging = 2;
  pipeline::ParametricPanel discs{"d", "discs", "standoff", {disc}};
  pipeline::ParametricOptions o;
  o.out_dir = out;
  // A page written outside the repository takes its figures with it.
  o.docs_page = out + "/doc/parametric.md";
  const fs::path repo_csv = fs::path(SOURCE_DIR) / "docs/figures/parametric/parametric.csv";
  const auto repo_csv_time = fs::last_write_time(repo_csv);
  o.jobs = 2;
  o.panels = {wedges, discs};
  const auto rows = pipeline::run_parametric(o);
  std::map<std::string, nlohmann::json> by_key;
  for (const auto& r : rows) by_key[r["key"].get<std::string>()] = r;
  auto beta = [&](const pipeline::ParametricPoint& p) {
    return by_key.at(pipeline::point_key(p))["beta_deg"].get<double>();
  };
  const double b10 = beta(small_wedge(10, 1.0)), b20 = beta(small_wedge(20, 1.0)),
               b10_inel = beta(small_wedge(10, 0.9));
  EXPECT_GT(b20, b10) << "beta increases with theta at fixed M";
  const double mach_angle = std::asin(1.0 / 3.0) / kDeg;
  EXPECT_GT(b10, mach_angle);
  EXPECT_GT(b20, mach_angle);
  EXPECT_GT(b10_inel, 10.0) << "the shock stays ahead of the wall";
  // Inelastic collisions cool the shocked gas and compress it more, so the
  // shock lies closer to the wall: a lower e gives a smaller beta.
  EXPECT_LT(b10_inel, b10);
  const double standoff = by_key.at(pipeline::point_key(disc))["standoff"].get<double>();
  EXPECT_GT(standoff, 0.0);
  EXPECT_TRUE(fs::exists(out + "/doc/parametric.md"));
  EXPECT_TRUE(fs::exists(out + "/doc/figures/parametric/parametric.csv"));
  EXPECT_TRUE(fs::exists(out + "/doc/figures/parametric/parametric_calibration.json"));
  EXPECT_EQ(fs::last_write_time(repo_csv), repo_csv_time) << "the repository's figures were rewritten";
}
