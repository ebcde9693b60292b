// The granular executable refuses scenes it cannot run (exit 2, one line
// naming the file and key), stops inelastic collapse with a RunError instead
// of hanging, and never replaces complete results with partial ones.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kExe = test_support::stage_exe("granular");

using test_support::CliRun;
using test_support::expect_refusal;
using test_support::has_temporaries;
using test_support::write_scene;

CliRun granular(const std::string& args) {
  return test_support::run_cli(kExe, args);
}
std::string fresh(const std::string& name) {
  return test_support::fresh_dir("granular_refuse_" + name);
}

}  // namespace

TEST(Refuse, ExtremeValuesAndCountsAreRefusedWithTheRange) {
  const std::string dir = fresh("extreme");
  std::string s =
      write_scene(dir, "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 1e308}\n");
  expect_refusal(granular("run " + s + " --out " + dir + "/out"),
                 s + ":2: key 'freestream.mach': expected a number in (0, 50]");
  s = write_scene(dir,
                  "box: {width: 100, height: 100}\ngranular: {particles: 9223372036854775808}\n");
  expect_refusal(granular("run " + s + " --out " + dir + "/out"),
                 s + ":2: key 'granular.particles'");
  s = write_scene(dir, "box: {width: 1e6, height: 1e6}\ngranular: {particles: 1000000000}\n");
  expect_refusal(granular("run " + s + " --out " + dir + "/out"),
                 "the limit is 5e+07 disks per run");
  s = write_scene(dir,
                  "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\ngranular: "
                  "{body_diameters: 1e5}\n");
  expect_refusal(granular("run " + s + " --dry-run"),
                 s + ": granular: key 'body_diameters': about");
  s = write_scene(dir, "box: {width: 10, height: 10}\ngranular: {particles: 1000}\n");
  expect_refusal(granular("run " + s + " --out " + dir + "/out"), "beyond close packing");
  EXPECT_FALSE(fs::exists(dir + "/out"));
  EXPECT_FALSE(has_temporaries(dir));
}

TEST(Refuse, InelasticCollapseStopsWithARunError) {
  // e = 0.01 without the TC model: the disks collapse into clusters that
  // collide infinitely often in finite time; this used to hang for ever.
  const std::string dir = fresh("collapse");
  const std::string s = write_scene(dir,
                                    "box: {width: 30, height: 30}\ngranular: {packing_fraction: "
                                    "0.4, restitution: 0.01, tc: 0, time: 1000}\n");
  const CliRun r = granular("run " + s + " --out " + dir + "/out");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("inelastic collapse"), std::string::npos) << r.err;
  EXPECT_LT(r.seconds, 30.0);
  EXPECT_FALSE(fs::exists(dir + "/out"));
  EXPECT_FALSE(has_temporaries(dir));
}

TEST(Refuse, InterruptedRunPutsItsPartialResultsBesideCompleteOnes) {
  const std::string dir = fresh("partial");
  const std::string out = dir + "/out";
  const std::string quick = write_scene(dir, R"(
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {body_diameters: 25, lattice_nx: 20, lattice_ny: 20, warmup: 0.2, averaging: 0.5, replicas: 1}
)");
  ASSERT_EQ(granular("run " + quick + " --out " + out).code, 0);
  const std::string complete = [&] {
    std::ifstream is(out + "/summary.json");
    return std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  }();
  const std::string long_run = dir + "/long.yaml";
  std::ofstream(long_run) << R"(
body: {kind: wedge, angle_deg: 10, length: 1.0}
freestream: {mach: 3.0}
granular: {body_diameters: 25, lattice_nx: 20, lattice_ny: 20, warmup: 0.2, averaging: 100000, replicas: 1}
)";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(kExe.c_str(), kExe.c_str(), "run", long_run.c_str(), "--out", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(3));  // averaging by then
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
  std::ifstream is(out + "/summary.json");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>()),
            complete);
  ASSERT_TRUE(fs::exists(out + ".partial/fields.vti"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + ".partial/summary.json"));
  EXPECT_TRUE(j["partial"].get<bool>());
  EXPECT_FALSE(has_temporaries(dir));
}

TEST(Refuse, OutContainingTheSceneIsRefused) {
  const std::string dir = fresh("overlap");
  const std::string s =
      write_scene(dir, "box: {width: 30, height: 30}\ngranular: {particles: 10}\n");
  expect_refusal(granular("run " + s + " --out " + dir),
                 "--out " + dir + ": equals, lies inside or contains the scene file");
  EXPECT_TRUE(fs::exists(s));
}

TEST(Refuse, PrecisionKeysOutOfRangeAreRefusedNamingTheKey) {
  // Precision on demand (docs/granular_flow.md): a target in (0, 1] body
  // lengths or `mesh`, a positive CPU budget, a positive averaging cap.
  const std::string dir = fresh("precision");
  const std::string head = "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\ngranular: ";
  for (const char* bad :
       {"{target_half_width: 0}", "{target_half_width: -0.01}", "{target_half_width: 2}",
        "{target_half_width: meshes}", "{target_half_width: [0.1]}"}) {
    const std::string s = write_scene(dir, head + bad + "\n");
    expect_refusal(granular("run " + s + " --dry-run"), s + ":3: key 'granular.target_half_width'");
  }
  for (const char* bad : {"{cpu_budget: 0}", "{cpu_budget: -5}", "{cpu_budget: soon}"}) {
    const std::string s = write_scene(dir, head + bad + "\n");
    expect_refusal(granular("run " + s + " --dry-run"), s + ":3: key 'granular.cpu_budget'");
  }
  for (const char* bad : {"{max_averaging: 0}", "{max_averaging: 1e9}"}) {
    const std::string s = write_scene(dir, head + bad + "\n");
    expect_refusal(granular("run " + s + " --dry-run"), s + ":3: key 'granular.max_averaging'");
  }
  EXPECT_FALSE(has_temporaries(dir));
}
