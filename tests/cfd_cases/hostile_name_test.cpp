// A scene name that a shell or gnuplot would run: the case's Allrun keeps
// it inside its comment line, and the run, its history plot and the
// OpenFOAM steps run nothing of it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/run_case.hpp"
#include "scene/io.hpp"
#include "scene/process.hpp"
#include "test_util.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kHostile =
    "x' . system(\"touch PWNED\") . ' `touch PWNED2` $(touch PWNED3)\ntouch PWNED4\n\"; touch "
    "PWNED5 #";

std::vector<std::string> pwned(const fs::path& d) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(d))
    if (e.path().filename().string().rfind("PWNED", 0) == 0) found.push_back(e.path().string());
  return found;
}

}  // namespace

TEST(HostileName, AllrunAndTheRunExecuteNothingOfIt) {
  scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 0.2, write_interval: 0.1}");
  s.name = kHostile;
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 2000, d + "/mesh");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  EXPECT_GT(r.steps, 0);
  // Allrun parses as shell (bash -n runs nothing) and the name stays on its
  // comment line.
  EXPECT_EQ(scene::ChildProcess({"bash", "-n", d + "/case/Allrun"}, {}).wait(), 0);
  const std::string allrun = scene::read_file(d + "/case/Allrun");
  const std::size_t first_end = allrun.find('\n');
  const std::string second_line =
      allrun.substr(first_end + 1, allrun.find('\n', first_end + 1) - first_end - 1);
  EXPECT_EQ(second_line.rfind("# shockgrain cfd case", 0), 0u) << allrun;
  EXPECT_EQ(allrun.find("\ntouch PWNED4"), std::string::npos) << allrun;
  EXPECT_EQ(pwned(d), std::vector<std::string>{});
}
