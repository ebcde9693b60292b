// The `granular` executable: help, version, exit codes, outputs, Ctrl-C, MPI.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "flow_support.hpp"
#include "scene/cli.hpp"
#include "scene/lattice.hpp"

namespace {

const std::string kExe = std::string(BIN_DIR) + "/granular";

struct Result {
  int code = -1;
  std::string out;  // stdout and stderr
};

Result sh(const std::string& args) {
  Result r;
  const std::string cmd = kExe + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string write_scene(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const char* kTiny = R"(
name: tiny
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {body_diameters: 25, lattice_nx: 20, lattice_ny: 20, warmup: 0.5, averaging: 0.5, replicas: 2}
)";

}  // namespace

TEST(FlowCli, HelpAndVersion) {
  const Result h = sh("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("run"), std::string::npos);
  const Result v = sh("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find(scene::version_string()), std::string::npos);
}

TEST(FlowCli, UsageErrorsExitTwo) {
  const Result bad = sh("run --bogus x.yaml");
  EXPECT_EQ(bad.code, 2) << bad.out;
  const Result none = sh("");
  EXPECT_EQ(none.code, 2) << none.out;
  const Result missing = sh("run /nonexistent/scene.yaml --out /tmp/x");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.out.find("granular: error: /nonexistent/scene.yaml: scene file not found"), std::string::npos)
      << missing.out;
  const std::string dir = flowtest::temp_dir("cli_bad");
  const std::string scene = write_scene(dir, "bad.yaml", "body: {kind: wedge}\nfreestream: {mach: 3}\ngranular: {restitution: 2}\n");
  const Result bad_key = sh("run " + scene + " --out " + dir);
  EXPECT_EQ(bad_key.code, 2);
  EXPECT_NE(bad_key.out.find("restitution"), std::string::npos) << bad_key.out;
}

TEST(FlowCli, DryRunPrintsTheResolvedScene) {
  const std::string dir = flowtest::temp_dir("cli_dry");
  const Result r = sh("run " + write_scene(dir, "tiny.yaml", kTiny) + " --dry-run");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("body_diameters"), std::string::npos);
  EXPECT_NE(r.out.find("inflow_speed"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/fields.vti"));
}

TEST(FlowCli, RunWritesFieldsAndSummary) {
  const std::string dir = flowtest::temp_dir("cli_run");
  const Result r = sh("run " + write_scene(dir, "tiny.yaml", kTiny) + " --out " + dir + "/out --np 2");
  ASSERT_EQ(r.code, 0) << r.out;
  const scene::Lattice lat = scene::read_vti(dir + "/out/fields.vti");
  EXPECT_TRUE(lat.has("volume_fraction_se"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/out/summary.json"));
  EXPECT_EQ(j["replicas"], 2);
  EXPECT_EQ(j["threads"], 2);
}

TEST(FlowCli, CtrlCKeepsTheFieldsAveragedSoFar) {
  const std::string dir = flowtest::temp_dir("cli_sigint");
  const std::string scene = write_scene(dir, "long.yaml", R"(
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {body_diameters: 25, lattice_nx: 20, lattice_ny: 20, warmup: 0.2, averaging: 100000, replicas: 1}
)");
  const std::string out = dir + "/out";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(kExe.c_str(), kExe.c_str(), "run", scene.c_str(), "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Long enough to be averaging (warm-up is a fraction of a second).
  std::this_thread::sleep_for(std::chrono::seconds(3));
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);  // a run that did not finish
  ASSERT_TRUE(std::filesystem::exists(out + "/fields.vti"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
  EXPECT_TRUE(j["interrupted"].get<bool>());
  EXPECT_GT(scene::read_vti(out + "/fields.vti").field("samples")[0], 0.0);
}

TEST(FlowCli, MpiRanksShareTheReplicas) {
  // The setup script installs Open MPI: a missing mpirun is a broken install, not a skip.
  ASSERT_EQ(std::system("command -v mpirun > /dev/null 2>&1"), 0) << "mpirun not on PATH";
  const std::string dir = flowtest::temp_dir("cli_mpi");
  const std::string scene = write_scene(dir, "tiny.yaml", kTiny);
  // Open MPI refuses root unless told; containers often run as root.
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -np 2 " +
                          kExe + " run " + scene + " --out " + dir + "/out > " + dir + "/log 2>&1";
  const int st = std::system(cmd.c_str());
  ASSERT_EQ(WEXITSTATUS(st), 0) << cmd;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/out/summary.json"));
  EXPECT_EQ(j["ranks"], 2);
  EXPECT_EQ(j["replicas"], 2);
  // Same seeds as the threaded run: identical collisions.
  const Result r = sh("run " + scene + " --out " + dir + "/threads --np 2");
  ASSERT_EQ(r.code, 0);
  const nlohmann::json k = nlohmann::json::parse(std::ifstream(dir + "/threads/summary.json"));
  EXPECT_EQ(j["collisions"], k["collisions"]);
}
