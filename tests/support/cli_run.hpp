#pragma once
// What the stages' refusal tests share: running an executable with its
// stderr and exit code captured, a fresh scratch folder with a scene file,
// and the checks that a refusal is one line with exit 2 and that nothing
// staged or temporary is left behind.
#include <string>

#include "scratch.hpp"

namespace test_support {

struct CliRun {
  int code = -1;       // exit status; -1 when the process did not exit normally
  std::string err;     // stderr (stdout is discarded)
  double seconds = 0;  // wall time of the run
};

// BIN_DIR/NAME: an executable of the build tree.
std::string stage_exe(const std::string& name);
// Runs `EXE ARGS` through the shell (ARGS is test-written text).
CliRun run_cli(const std::string& exe, const std::string& args);

// DIR/scene.yaml holding TEXT; returns its path.
std::string write_scene(const std::string& dir, const std::string& text);

// Exit 2 with exactly one line on stderr, which contains NEEDLE.
void expect_refusal(const CliRun& r, const std::string& needle);
// True when DIR holds a staging folder, a moved-aside old output or a
// temporary file (names containing .staging-, .old- or .tmp.).
bool has_temporaries(const std::string& dir);

}  // namespace test_support
