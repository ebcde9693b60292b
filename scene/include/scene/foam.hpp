#pragma once
// Running OpenFOAM applications: each in the OpenFOAM environment (its
// etc/bashrc sourced by bash), in the case directory, writing
// CASE/log.<application> there, as OpenFOAM's RunFunctions do, so that a
// user can rerun a step by hand. Used by meshgen (checkMesh; gmshToFoam in its tests) and
// cfd_cases (blockMesh, decomposePar, rhoCentralFoam, reconstructPar).
#include <string>
#include <vector>

#include "scene/process.hpp"

namespace scene {

// The OpenFOAM bashrc: $SHOCKGRAIN_FOAM_BASHRC, else $WM_PROJECT_DIR/etc/bashrc,
// else /usr/share/openfoam/etc/bashrc. RunError if none exists.
std::string foam_bashrc();

// The argv that runs `app args` in the OpenFOAM environment; np > 1 runs it
// under mpirun with -parallel. bash receives the bashrc, the application and
// its arguments as positional parameters, never as shell text.
std::vector<std::string> foam_argv(const std::string& bashrc, const std::string& app,
                                   const std::vector<std::string>& args, int np);

// A started OpenFOAM application in case_dir, logging to case_dir/log.<app>.
class FoamProcess {
 public:
  FoamProcess(const std::string& case_dir, const std::string& app,
              const std::vector<std::string>& args, int np = 1);

  bool poll() { return child_.poll(); }
  int wait() { return child_.wait(); }
  void terminate() { child_.terminate(); }
  int exit_code() const { return child_.exit_code(); }
  double cpu_seconds() const { return child_.cpu_seconds(); }
  double wall_seconds() const { return child_.wall_seconds(); }
  ChildTimes times() const { return child_.times(); }
  const std::string& log_path() const { return child_.log_path(); }

 private:
  ChildProcess child_;
};

// Runs to completion; RunError naming the log and its last lines on failure.
ChildTimes run_foam(const std::string& case_dir, const std::string& app,
                    const std::vector<std::string>& args, int np = 1);

}  // namespace scene
