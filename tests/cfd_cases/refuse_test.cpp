// The cfd executable refuses subsonic scenes and an --out that would wipe
// its input (exit 2, one line), and a failed or interrupted `cfd run`
// leaves the previous case in --out untouched.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kExe = test_support::stage_exe("cfd");

using test_support::CliRun;
using test_support::expect_refusal;
using test_support::has_temporaries;
using test_support::write_scene;

CliRun cfd(const std::string& args) {
  return test_support::run_cli(kExe, args);
}
std::string fresh(const std::string& name) {
  return test_support::fresh_dir("cfd_refuse_" + name);
}

// A time directory the solver wrote: a name that is a whole positive number
// ("0.orig", written with the case before the solver starts, is not).
bool is_positive_time(const std::string& name) {
  char* end = nullptr;
  const double t = std::strtod(name.c_str(), &end);
  return !name.empty() && *end == '\0' && t > 0.0;
}

// True once a staging case beside --out holds an entry whose name passes
// `wanted`, whatever the machine's speed.
bool wait_for_staged(const std::string& dir, const std::function<bool(const std::string&)>& wanted,
                     std::chrono::seconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < until) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().filename().string().find(".staging-") == std::string::npos) continue;
      std::error_code ec;
      for (const auto& t : fs::directory_iterator(e.path(), ec))
        if (wanted(t.path().filename().string())) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

constexpr const char* kWedge =
    "body: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n";

}  // namespace

TEST(Refuse, SubsonicSceneIsRefusedBeforeOpenFoam) {
  const std::string dir = fresh("subsonic");
  const std::string s =
      write_scene(dir, "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 0.8}\n");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/case"),
                 s + ": key 'freestream.mach': cfd run needs a supersonic free stream");
  EXPECT_FALSE(fs::exists(dir + "/case"));
}

TEST(Refuse, OutEqualToOrAroundTheMeshIsRefused) {
  const std::string dir = fresh("overlap");
  const std::string s = write_scene(dir, kWedge);
  fs::create_directories(dir + "/mesh/constant/polyMesh");
  std::ofstream(dir + "/mesh/constant/polyMesh/faces") << "keep me\n";
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/mesh"),
                 "--out " + dir + "/mesh: equals, lies inside or contains the --mesh folder");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/mesh/case"),
                 "--mesh folder");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh/ --out " + dir), "--mesh folder");
  EXPECT_TRUE(fs::exists(dir + "/mesh/constant/polyMesh/faces"));
}

namespace {

// Runs `cfd run` on a case that never settles, sends SIGINT once the
// staging case holds an entry that passes `signal_when`, and checks that the
// run ends as an interrupted run: exit 1, the previous case untouched, the
// interrupted one kept beside it, no temporaries.
void expect_clean_interrupt(const std::string& name,
                            const std::function<bool(const std::string&)>& signal_when) {
  const std::string dir = fresh(name);
  const std::string s =
      write_scene(dir, std::string(kWedge) +
                           "cfd: {end_time: 1000, write_interval: 1, steady_tol: 1e-300, "
                           "force_tol: 1e-300}\n");  // never settles: only the signal ends it
  ASSERT_EQ(cfd("blockmesh " + s + " --cells 2000 --out " + dir + "/mesh").code, 0);
  const std::string out = dir + "/case";
  fs::create_directories(out);
  std::ofstream(out + "/summary.json") << "{\"previous\": true}\n";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string mesh = dir + "/mesh";
    execl(kExe.c_str(), kExe.c_str(), "run", s.c_str(), "--mesh", mesh.c_str(), "--out",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(wait_for_staged(dir, signal_when, std::chrono::seconds(120)));
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
  std::ifstream is(out + "/summary.json");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>()),
            "{\"previous\": true}\n");
  EXPECT_TRUE(fs::exists(out + ".failed"));
  EXPECT_FALSE(has_temporaries(dir));
}

}  // namespace

TEST(Refuse, InterruptedRunKeepsThePreviousCase) {
  expect_clean_interrupt("interrupt", is_positive_time);
}

// A Ctrl-C while the case is still being written or the solver is starting:
// the stop request can land before the solver watches controlDict, and the
// run must still end as an interrupted run within the watchdog's grace.
TEST(Refuse, InterruptBeforeTheSolverRunsEndsAsAnInterruptedRun) {
  expect_clean_interrupt("interrupt_early", [](const std::string& n) { return n == "0.orig"; });
}

TEST(Refuse, FinishedRunSummaryNamesTheFolderItWasMovedTo) {
  const std::string dir = fresh("finished");
  const std::string s =
      write_scene(dir, std::string(kWedge) + "cfd: {end_time: 0.2, write_interval: 0.1}\n");
  ASSERT_EQ(cfd("blockmesh " + s + " --cells 500 --out " + dir + "/mesh").code, 0);
  const std::string out = dir + "/case";
  ASSERT_EQ(cfd("run " + s + " --mesh " + dir + "/mesh --out " + out).code, 0);
  std::ifstream is(out + "/summary.json");
  const std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"case_dir\": \"" + out + "\""), std::string::npos) << text;
  EXPECT_EQ(text.find(".staging-"), std::string::npos) << text;
  EXPECT_FALSE(has_temporaries(dir));
}
