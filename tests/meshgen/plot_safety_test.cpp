// meshgen end to end on a coarse uniform wedge grid: a scene name that
// gnuplot or a shell would run is drawn in the titles and runs nothing, and
// summary.json accounts for the CPU of gmsh and of the OpenFOAM children.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "meshgen/mesh.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/io.hpp"
#include "scene/process.hpp"
#include "shock_fixtures.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kCoarseH = 0.05;  // body lengths: a few hundred cells

const std::string kHostile =
    "x' . system(\"touch PWNED\") . ' `touch PWNED2` $(touch PWNED3)\n'; system('touch PWNED4') #";

std::vector<std::string> pwned(const fs::path& d) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(d))
    if (e.path().filename().string().rfind("PWNED", 0) == 0) found.push_back(e.path().string());
  return found;
}

meshgen::MeshRequest coarse_uniform() {
  meshgen::MeshRequest r;
  r.uniform = true;
  r.h_min = kCoarseH;
  return r;
}

}  // namespace

TEST(PlotSafety, HostileSceneNameIsDrawnNotRun) {
  ASSERT_FALSE(scene::find_program("gnuplot").empty())
      << "gnuplot is required for this test (meshgen draws mesh.png with it); install gnuplot 5";
  scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  s.name = kHostile;
  const std::string dir = meshgen_test::fresh_dir("hostile_name");
  const meshgen::MeshResult res = meshgen::generate_mesh(s, coarse_uniform(), dir);
  EXPECT_TRUE(res.details.at("plot_error").is_null()) << res.details.at("plot_error");
  for (const char* png : {"mesh.png", "mesh_zoom.png"})
    EXPECT_TRUE(fs::exists(fs::path(dir) / png) && fs::file_size(fs::path(dir) / png) > 0) << png;
  EXPECT_EQ(pwned(dir), std::vector<std::string>{});
  fs::remove_all(dir);
}

// cpu_seconds: everything meshgen's process (its threads: the grid files,
// the plots' data) and its children (gmsh, checkMesh, gnuplot) spent, so at
// least gmsh's and checkMesh's CPU and at most what the call cost in all.
TEST(CpuAccounting, SummaryCountsTheProcessAndItsChildren) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const std::string dir = meshgen_test::fresh_dir("cpu_accounting");
  const scene::CpuStopwatch call;
  (void)meshgen::generate_mesh(s, coarse_uniform(), dir);
  const double spent = call.seconds();
  const nlohmann::json j = nlohmann::json::parse(scene::read_file(dir + "/summary.json"));
  const double gmsh = j.at("gmsh_cpu_seconds").get<double>(),
               foam = j.at("foam_cpu_seconds").get<double>(), cpu = j.at("cpu_seconds").get<double>();
  EXPECT_GT(gmsh, 0.0);
  EXPECT_GT(foam, 0.0);  // checkMesh takes tens of milliseconds
  EXPECT_GE(cpu, gmsh + foam);
  EXPECT_LE(cpu, spent);
  EXPECT_TRUE(j.contains("seconds"));
  fs::remove_all(dir);
}
