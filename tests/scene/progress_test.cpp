// Progress and log lines: plain lines off a terminal, silence in CI, and
// Ctrl-C handling of the shared CLI plumbing.
#include "scene/progress.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scratch.hpp"

namespace {

// Captures what `body` writes to stderr (fd 2).
template <class F>
std::string capture_stderr(F body) {
  // One file per test process: ctest runs tests in parallel.
  const auto path =
      (test_support::scratch_root() / ("progress_capture_" + std::to_string(::getpid()) + ".txt"))
          .string();
  std::fflush(stderr);
  const int saved = ::dup(2);
  std::FILE* f = std::fopen(path.c_str(), "w");
  ::dup2(::fileno(f), 2);
  body();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::fclose(f);
  std::ifstream is(path);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

}  // namespace

TEST(Progress, PlainLinesOffATerminal) {
  ::unsetenv("CI");
  const auto out = capture_stderr([] {
    scene::Progress p("granular", 100, "collisions");
    p.update(50);
    p.finish("ok");
    scene::log_line("hello");
  });
  EXPECT_NE(out.find("granular: done in"), std::string::npos) << out;
  EXPECT_NE(out.find("hello\n"), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << "no terminal redraws in a file";
}

TEST(Progress, QuietInCi) {
  ::setenv("CI", "true", 1);
  const auto out = capture_stderr([] {
    scene::Progress p("granular", 100);
    p.update(100);
    p.finish();
    scene::log_line("chatter");
    scene::log_line("an error everyone must see", true);
  });
  ::unsetenv("CI");
  EXPECT_EQ(out, "an error everyone must see\n");
}

TEST(Cli, ExitCodesFollowTheContract) {
  const auto quiet = [](auto f) { return capture_stderr(f); };
  int rc = -1;
  const auto msg = quiet([&] {
    rc = scene::run_guarded("tool",
                            []() -> int { throw scene::InputError("scene.yaml:3: key 'x': bad"); });
  });
  EXPECT_EQ(rc, 2);
  EXPECT_EQ(msg, "tool: error: scene.yaml:3: key 'x': bad\n");
  quiet(
      [&] { rc = scene::run_guarded("tool", []() -> int { throw scene::RunError("diverged"); }); });
  EXPECT_EQ(rc, 1);
  EXPECT_EQ(scene::run_guarded("tool", [] { return 0; }), 0);
}

TEST(Cli, OneLineEscapesWhatWouldSplitTheMessage) {
  EXPECT_EQ(scene::one_line("scene\nname\twith\x7f"), "scene\\nname?with?");
}

TEST(Cli, FirstInterruptSetsTheFlag) {
  scene::install_interrupt_handler();
  scene::clear_interrupt();
  EXPECT_FALSE(scene::interrupted());
  std::raise(SIGINT);
  EXPECT_TRUE(scene::interrupted());
  scene::clear_interrupt();
  std::signal(SIGINT, SIG_DFL);
}

// A process stuck where nothing polls the flag (here: asleep) is stopped by
// the watchdog one grace period after the first signal, with one line and
// the interrupt's exit code; without the watchdog it would sleep on and exit 0.
TEST(Cli, WatchdogStopsAProcessThatIgnoresTheFirstInterrupt) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        scene::install_interrupt_handler(1);
        std::raise(SIGINT);
        for (int i = 0; i < 30; ++i) ::sleep(1);  // a sleep interrupted by the alarm resumes
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(130), "did not stop within its grace period");
}
