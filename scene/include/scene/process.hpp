#pragma once
// Child processes without a shell: an argv vector is executed directly, so no
// path, scene name or label is ever parsed as shell text. Every external
// program of the toolchain (OpenFOAM applications, mpirun, gnuplot) is
// started through ChildProcess.
#include <sys/types.h>

#include <string>
#include <vector>

namespace scene {

struct ChildOptions {
  std::string work_dir;  // working directory of the child; empty: ours
  std::string log_path;  // stdout and stderr (truncated); empty: /dev/null
};

// Wall and CPU time of a finished child. CPU is user + system seconds of the
// child and every descendant it waited for (mpirun's ranks, a shell's exec).
struct ChildTimes {
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
};

// A started program. The child has its own process group, so a Ctrl-C at the
// terminal reaches only us (we stop it cleanly); it is sent SIGTERM if we die
// (PR_SET_PDEATHSIG), and its group is sent SIGTERM when the object is
// destroyed before the child has been reaped. stdin is /dev/null.
class ChildProcess {
 public:
  // argv[0] is a path or a name looked up on PATH. RunError when it cannot
  // be started (not found, not executable, no such work_dir).
  ChildProcess(const std::vector<std::string>& argv, const ChildOptions& options);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();

  // Non-blocking; true once the child has exited (exit_code() then valid).
  bool poll();
  // Blocks until the child exits; its exit code, 128 + signal if killed.
  int wait();
  void terminate();  // SIGTERM to the process group

  int exit_code() const { return code_; }
  // Valid once the child has been reaped; 0 before.
  double cpu_seconds() const { return times_.cpu_seconds; }
  double wall_seconds() const { return times_.wall_seconds; }
  ChildTimes times() const { return times_; }
  const std::string& log_path() const { return log_; }
  const std::string& program() const { return program_; }

 private:
  bool reap(int flags);

  pid_t pid_ = -1;
  bool done_ = false;
  int code_ = -1;
  ChildTimes times_;
  double started_ = 0.0;  // steady clock, seconds
  std::string log_;
  std::string program_;
};

// Runs argv to completion. RunError naming the program, its exit code and
// the log (when there is one) on a non-zero exit.
ChildTimes run_child(const std::vector<std::string>& argv, const ChildOptions& options);

// The executable that argv[0] names: itself when it holds a '/', else the
// first executable PATH entry; empty when there is none.
std::string find_program(const std::string& name);

// The last `lines` non-empty lines of a text file, each on its own indented
// line (for error messages); "(no log)" when it cannot be read.
std::string log_tail(const std::string& path, int lines = 15);

}  // namespace scene
