#pragma once
// Runs an executable with a wall-clock limit and captures its stderr, for
// the fuzz suite: the outcome tells a clean refusal from a crash or a hang.
#include <string>
#include <vector>

namespace fuzz {

struct Outcome {
  int code = -1;      // exit status when it exited
  int signal = 0;     // terminating signal, 0 if it exited
  bool hung = false;  // killed at the time limit
  std::string err;    // everything written to stderr
  double seconds = 0;
};

// Runs argv[0] (a path) with argv in its own process group (so a child such
// as meshgen's gmsh process is killed with it), stdout to /dev/null, stderr
// to `err_file`.
Outcome run_capture(const std::vector<std::string>& argv, double timeout_s,
                    const std::string& err_file);

}  // namespace fuzz
