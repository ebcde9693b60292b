// A scene name that gnuplot or a shell would run as a command: shockfit
// draws it in the picture title and runs nothing. Needs the real gnuplot;
// fails, naming it, when it is missing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/process.hpp"
#include "scratch.hpp"
#include "synthetic.hpp"

namespace fs = std::filesystem;

namespace {

// The name as YAML writes it (double-quoted: \" is an escape), and as the
// scene holds it. A newline, which would end a gnuplot command line, is
// refused by the scene parser before any stage runs (scene HostileScene
// tests); everything else a plain name may hold is here.
constexpr const char* kYamlName =
    R"("x' . system(\"touch PWNED\") . ' `touch PWNED2` $(touch PWNED3) '; system('touch PWNED4') #")";
constexpr const char* kName =
    "x' . system(\"touch PWNED\") . ' `touch PWNED2` $(touch PWNED3) '; system('touch PWNED4') #";

std::vector<std::string> pwned(const fs::path& d) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(d))
    if (e.path().filename().string().rfind("PWNED", 0) == 0) found.push_back(e.path().string());
  return found;
}

}  // namespace

TEST(PlotSafety, HostileSceneNameIsDrawnNotRun) {
  ASSERT_FALSE(scene::find_program("gnuplot").empty())
      << "gnuplot is required for this test (shockfit draws shock.png with it); install gnuplot 5";
  const fs::path dir =
      test_support::scratch_root() / ("shockfit_test_" + std::to_string(::getpid()) + "_hostile");
  fs::remove_all(dir);
  fs::create_directories(dir);
  // wedge_M3_10 under the hostile name.
  std::string yaml = scene::read_file(std::string(SOURCE_DIR) + "/pipeline/cases/wedge_M3_10.yaml");
  const std::string name_line = "name: wedge_M3_10";
  ASSERT_NE(yaml.find(name_line), std::string::npos);
  yaml.replace(yaml.find(name_line), name_line.size(), std::string("name: ") + kYamlName);
  scene::write_file_atomic((dir / "scene.yaml").string(), yaml);
  const scene::Scene s = scene::load_scene((dir / "scene.yaml").string());
  ASSERT_EQ(s.name, kName);
  // Its exact oblique shock on a coarse lattice.
  constexpr double kLatticeStep = 0.02;
  const double theta = s.body->angle_deg * std::numbers::pi / 180.0;
  const double beta = *scene::oblique_shock_beta(s.freestream.mach, theta, s.freestream.gamma);
  const double r2 = scene::oblique_density_ratio(s.freestream.mach, beta, s.freestream.gamma);
  scene::Lattice lat = shockfit_test::domain_lattice(s, kLatticeStep);
  shockfit_test::fill(
      lat, "volume_fraction",
      [&](double x, double y) {
        return y * std::cos(beta) - x * std::sin(beta) > 0 ? 0.1 : 0.1 * r2;
      },
      0.0, 1);
  scene::write_vti(lat, (dir / "fields.vti").string());

  // Run in `dir`, so that a command run by accident lands there.
  scene::ChildProcess shockfit(
      {std::string(BIN_DIR) + "/shockfit", "scene.yaml", "--fields", "fields.vti", "--out", "out"},
      {dir.string(), (dir / "log").string()});
  ASSERT_EQ(shockfit.wait(), 0) << scene::read_file((dir / "log").string());
  const std::string log = scene::read_file((dir / "log").string());
  EXPECT_EQ(log.find("no PNG written"), std::string::npos) << log;
  ASSERT_TRUE(fs::exists(dir / "out" / "shock.png")) << log;
  constexpr std::uintmax_t kSomePicture = 1000;  // bytes; an empty PNG is a few hundred
  EXPECT_GT(fs::file_size(dir / "out" / "shock.png"), kSomePicture);
  EXPECT_EQ(pwned(dir), std::vector<std::string>{});
  const nlohmann::json j =
      nlohmann::json::parse(scene::read_file((dir / "out" / "summary.json").string()));
  EXPECT_EQ(j.at("scene"), kName);
  fs::remove_all(dir);
}
