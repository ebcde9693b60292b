// The shared launcher: argv reaches the program verbatim (no shell), exit
// codes, CPU time of the child and its descendants, the OpenFOAM
// environment without text interpolation.
#include "scene/process.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "scene/errors.hpp"
#include "scene/foam.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  return test_support::fresh_dir("scene_test_process_" + std::to_string(::getpid()) + "_" + name);
}

// Text that a shell (or gnuplot) would turn into commands.
const std::string kHostile =
    "x' . system(\"touch PWNED\") . ' `touch PWNED2` $(touch PWNED3); touch PWNED4";

bool any_pwned(const fs::path& d) {
  for (const auto& e : fs::directory_iterator(d))
    if (e.path().filename().string().rfind("PWNED", 0) == 0) return true;
  return false;
}

}  // namespace

TEST(Process, ArgumentsReachTheProgramVerbatim) {
  const fs::path d = fresh_dir("argv");
  scene::ChildProcess p({"printf", "%s", kHostile}, {d.string(), (d / "log").string()});
  EXPECT_EQ(p.wait(), 0);
  EXPECT_EQ(scene::read_file((d / "log").string()), kHostile);
  EXPECT_FALSE(any_pwned(d));
  fs::remove_all(d);
}

TEST(Process, RunsInItsWorkingDirectory) {
  const fs::path d = fresh_dir("cwd");
  const fs::path sub = d / "it's $(here)";
  fs::create_directories(sub);
  scene::ChildProcess p({"pwd"}, {sub.string(), (d / "log").string()});
  EXPECT_EQ(p.wait(), 0);
  EXPECT_EQ(scene::read_file((d / "log").string()), fs::canonical(sub).string() + "\n");
  fs::remove_all(d);
}

TEST(Process, ExitCodesAndSignals) {
  const fs::path d = fresh_dir("codes");
  scene::ChildProcess three({"bash", "-c", "exit 3"}, {});
  EXPECT_EQ(three.wait(), 3);
  scene::ChildProcess sleeper({"sleep", "30"}, {});
  EXPECT_FALSE(sleeper.poll());
  sleeper.terminate();
  EXPECT_EQ(sleeper.wait(), 128 + SIGTERM);
  EXPECT_THROW(scene::run_child({"bash", "-c", "exit 1"}, {}), scene::RunError);
  fs::remove_all(d);
}

TEST(Process, DestructionStopsTheWholeGroup) {
  // bash waits on a grandchild; SIGTERM to the group ends both at once.
  constexpr double kPromptSeconds = 5.0;
  const auto t0 = std::chrono::steady_clock::now();
  { scene::ChildProcess p({"bash", "-c", "sleep 30 & wait"}, {}); }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            kPromptSeconds);
}

TEST(Process, AProgramThatCannotStartIsARunError) {
  const fs::path d = fresh_dir("missing");
  try {
    scene::ChildProcess p({"shockgrain-no-such-program"}, {});
    ADD_FAILURE() << "started";
  } catch (const scene::RunError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot start shockgrain-no-such-program: not found on PATH");
  }
  try {
    scene::ChildProcess p({"true"}, {(d / "absent").string(), ""});
    ADD_FAILURE() << "started";
  } catch (const scene::RunError& e) {
    EXPECT_NE(std::string(e.what()).find((d / "absent").string()), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}

TEST(Process, CpuSecondsIncludeWaitedForDescendants) {
  // The busy loop runs in a subshell that bash forks and reaps, as mpirun
  // reaps its ranks; the child itself only waits.
  constexpr double kMinBusyCpu = 0.05;  // the loop takes about 0.3 s of CPU
  scene::ChildProcess p({"bash", "-c", "(i=0; while ((i < 200000)); do ((i++)); done); true"}, {});
  EXPECT_EQ(p.wait(), 0);
  EXPECT_GT(p.cpu_seconds(), kMinBusyCpu);
  EXPECT_GT(p.wall_seconds(), 0.0);
}

TEST(Foam, ArgvHoldsNamesAsParametersNotShellText) {
  const auto serial = scene::foam_argv("/o'f/bashrc", "checkMesh", {kHostile}, 1);
  ASSERT_EQ(serial.size(), 7u);
  EXPECT_EQ(serial[0], "bash");
  EXPECT_EQ(serial[1], "-c");
  EXPECT_EQ(serial[2].find("o'f"), std::string::npos);
  EXPECT_EQ(serial[4], "/o'f/bashrc");
  EXPECT_EQ(serial[5], "checkMesh");
  EXPECT_EQ(serial[6], kHostile);
  const auto parallel = scene::foam_argv("/b", "rhoCentralFoam", {}, 4);
  ASSERT_GE(parallel.size(), 10u);
  EXPECT_EQ(parallel[5], "mpirun");
  EXPECT_EQ(parallel[7], "4");
  EXPECT_EQ(parallel[parallel.size() - 2], "rhoCentralFoam");
  EXPECT_EQ(parallel.back(), "-parallel");
}

TEST(Foam, RunsInTheEnvironmentOfTheBashrc) {
  const fs::path d = fresh_dir("foam");
  const fs::path case_dir = d / "case 'a' $(touch PWNED)";
  fs::create_directories(case_dir);
  // A stand-in bashrc: exports a variable and records how many arguments it
  // was sourced with (OpenFOAM's evaluates them as settings: must be none).
  const fs::path bashrc = d / "bashrc";
  scene::write_file_atomic(bashrc.string(),
                           "export SHOCKGRAIN_TEST_MARK=sourced\necho $# > sourced_args\n");
  const char* before = std::getenv("SHOCKGRAIN_FOAM_BASHRC");
  const std::string saved = before ? before : "";
  ::setenv("SHOCKGRAIN_FOAM_BASHRC", bashrc.c_str(), 1);
  const scene::ChildTimes t =
      scene::run_foam(case_dir.string(), "printenv", {"SHOCKGRAIN_TEST_MARK"});
  EXPECT_GE(t.wall_seconds, 0.0);
  EXPECT_EQ(scene::read_file((case_dir / "log.printenv").string()), "sourced\n");
  EXPECT_EQ(scene::read_file((case_dir / "sourced_args").string()), "0\n");
  try {
    scene::run_foam(case_dir.string(), "false", {});
    ADD_FAILURE() << "no error";
  } catch (const scene::RunError& e) {
    EXPECT_NE(std::string(e.what()).find((case_dir / "log.false").string()), std::string::npos)
        << e.what();
  }
  if (before)
    ::setenv("SHOCKGRAIN_FOAM_BASHRC", saved.c_str(), 1);
  else
    ::unsetenv("SHOCKGRAIN_FOAM_BASHRC");
  EXPECT_FALSE(any_pwned(d));
  EXPECT_FALSE(any_pwned(case_dir));
  fs::remove_all(d);
}
