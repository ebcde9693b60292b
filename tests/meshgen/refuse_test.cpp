// meshgen refuses what it cannot mesh before gmsh starts (exit 2, one line
// naming the file, the key or flag, and the estimate), honours Ctrl-C while
// gmsh meshes, and never replaces a good mesh with a failed one.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "cli_run.hpp"
#include "shock_fixtures.hpp"

namespace fs = std::filesystem;

namespace {

using test_support::CliRun;
using test_support::expect_refusal;
using test_support::has_temporaries;
using test_support::write_scene;

CliRun meshgen(const std::string& args) {
  return test_support::run_cli(test_support::stage_exe("meshgen"), args);
}

constexpr const char* kWedge =
    "body: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n";

}  // namespace

TEST(Refuse, TinyCellsAndHugeDomainsAreRefusedWithTheEstimate) {
  const std::string dir = meshgen_test::fresh_dir("refuse_size");
  const std::string scene = write_scene(dir, kWedge);
  expect_refusal(meshgen(scene + " --uniform --h-min 1e-9 --out " + dir + "/out"),
                 "h_min 1e-09 is below the smallest cell size meshgen accepts");
  expect_refusal(meshgen(scene + " --uniform --h-min 2e-4 --out " + dir + "/out"),
                 "above meshgen's limit of 5e+06");
  const std::string huge = write_scene(
      dir, std::string(kWedge) +
               "domain: {xmin: -1e6, xmax: 1e6, ymin: 0, ymax: 1e6, symmetric: true}\n");
  const CliRun r = meshgen(huge + " --uniform --out " + dir + "/out");
  expect_refusal(r, huge + ": mesh: the grid would have about");
  EXPECT_FALSE(fs::exists(dir + "/out"));
  EXPECT_FALSE(has_temporaries(dir));
}

TEST(Refuse, NonFiniteFlagsAreUsageErrors) {
  const std::string dir = meshgen_test::fresh_dir("refuse_flags");
  const std::string scene = write_scene(dir, kWedge);
  for (const char* v : {"nan", "inf", "-1", "0"}) {
    expect_refusal(meshgen(scene + " --uniform --target-cells " + v + " --out " + dir + "/out"),
                   "--target-cells");
    expect_refusal(meshgen(scene + " --uniform --h-min " + v + " --out " + dir + "/out"),
                   "--h-min");
  }
  expect_refusal(meshgen(scene + " --uniform --target-cells 1e9 --out " + dir + "/out"),
                 "target_cells must be");
}

TEST(Refuse, SubsonicSceneIsRefused) {
  const std::string dir = meshgen_test::fresh_dir("refuse_subsonic");
  const std::string scene =
      write_scene(dir, "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 0.5}\n");
  expect_refusal(meshgen(scene + " --uniform --out " + dir + "/out"),
                 scene + ": key 'freestream.mach': meshgen needs a supersonic free stream");
  expect_refusal(meshgen(scene + " --uniform --dry-run --out " + dir + "/out"), "supersonic");
}

TEST(Refuse, CtrlCStopsGmshAndKeepsThePreviousMesh) {
  const std::string dir = meshgen_test::fresh_dir("refuse_sigint");
  const std::string scene = meshgen_test::case_path("wedge_M3_10");
  const std::string out = dir + "/out";
  const CliRun first = meshgen(scene + " --uniform --h-min 0.05 --out " + out);
  ASSERT_EQ(first.code, 0) << first.err;
  const auto stamp = fs::last_write_time(out + "/constant/polyMesh/points");
  // About 3e5 cells: gmsh takes ~15 s, so the signal arrives mid-mesh.
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string exe = std::string(BIN_DIR) + "/meshgen";
    execl(exe.c_str(), exe.c_str(), scene.c_str(), "--uniform", "--h-min", "0.0015", "--out",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const auto t0 = std::chrono::steady_clock::now();
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
  EXPECT_LT(waited, 2.0);  // honoured within a poll, not after gmsh finishes
  EXPECT_EQ(fs::last_write_time(out + "/constant/polyMesh/points"), stamp);
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
  EXPECT_FALSE(has_temporaries(dir));
}
