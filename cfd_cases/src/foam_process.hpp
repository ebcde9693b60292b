#pragma once
// Running OpenFOAM applications: each in the OpenFOAM environment (its
// etc/bashrc sourced by bash), in the case directory, writing
// log.<application> there, exactly as a user would rerun the step by hand.
#include <string>
#include <sys/types.h>

namespace cfd {

// The OpenFOAM bashrc: $SHOCKGRAIN_FOAM_BASHRC, else $WM_PROJECT_DIR/etc/bashrc,
// else /usr/share/openfoam/etc/bashrc. RunError if none exists.
std::string foam_bashrc();

// The shell line that runs `app args` for the case (used by Allrun too).
// np > 1 runs it under mpirun with -parallel.
std::string foam_command(const std::string& app, const std::string& args, int np);

// A started OpenFOAM application. The child has its own process group, so a
// Ctrl-C at the terminal reaches only us (we stop it cleanly), and it is sent
// SIGTERM if we die.
class FoamProcess {
 public:
  FoamProcess(const std::string& case_dir, const std::string& app, const std::string& args, int np);
  FoamProcess(const FoamProcess&) = delete;
  FoamProcess& operator=(const FoamProcess&) = delete;
  ~FoamProcess();

  // Non-blocking; true once the process has exited (exit_code() then valid).
  bool poll();
  // Blocks until it exits; returns the exit code (128 + signal if killed).
  int wait();
  void terminate();  // SIGTERM to the process group
  int exit_code() const { return code_; }
  const std::string& log_path() const { return log_; }

 private:
  pid_t pid_ = -1;
  bool done_ = false;
  int code_ = -1;
  std::string log_;
};

// Runs to completion; RunError naming the log and its last lines on failure.
void run_foam(const std::string& case_dir, const std::string& app, const std::string& args, int np = 1);

// The last `lines` lines of a text file (for error messages).
std::string log_tail(const std::string& path, int lines = 15);

}  // namespace cfd
