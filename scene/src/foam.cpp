#include "scene/foam.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "scene/errors.hpp"

namespace scene {

namespace {

constexpr const char* kDefaultBashrc = "/usr/share/openfoam/etc/bashrc";

// bash runs this text, which is constant: the bashrc, the application and
// its arguments arrive as $1, $2, ... The positional parameters are cleared
// before sourcing because OpenFOAM's bashrc evaluates its own arguments as
// settings (etc/config.sh/setup: `_foamEval "$@"`), and a sourced file sees
// the caller's parameters.
constexpr const char* kFoamScript =
    "bashrc=$1; shift; command=(\"$@\"); set --; "
    ". \"$bashrc\" > /dev/null 2>&1; exec \"${command[@]}\"";

}  // namespace

std::string foam_bashrc() {
  std::vector<std::string> candidates;
  if (const char* e = std::getenv("SHOCKGRAIN_FOAM_BASHRC")) candidates.emplace_back(e);
  if (const char* e = std::getenv("WM_PROJECT_DIR"))
    candidates.push_back(std::string(e) + "/etc/bashrc");
  candidates.emplace_back(kDefaultBashrc);
  for (const auto& c : candidates)
    if (std::filesystem::exists(c)) return c;
  throw RunError(std::string("OpenFOAM environment not found (tried $SHOCKGRAIN_FOAM_BASHRC, "
                             "$WM_PROJECT_DIR/etc/bashrc, ") +
                 kDefaultBashrc + ")");
}

std::vector<std::string> foam_argv(const std::string& bashrc, const std::string& app,
                                   const std::vector<std::string>& args, int np) {
  std::vector<std::string> argv{"bash", "-c", kFoamScript, "bash", bashrc};
  if (np > 1) {
    // --oversubscribe: more ranks than cores is fine for small cases; root
    // needs --allow-run-as-root (containers, CI).
    argv.insert(argv.end(), {"mpirun", "-np", std::to_string(np), "--oversubscribe"});
    if (::geteuid() == 0) argv.emplace_back("--allow-run-as-root");
  }
  argv.push_back(app);
  if (np > 1) argv.emplace_back("-parallel");
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

FoamProcess::FoamProcess(const std::string& case_dir, const std::string& app,
                         const std::vector<std::string>& args, int np)
    : child_(foam_argv(foam_bashrc(), app, args, np),
             ChildOptions{case_dir, case_dir + "/log." + app}) {}

ChildTimes run_foam(const std::string& case_dir, const std::string& app,
                    const std::vector<std::string>& args, int np) {
  FoamProcess p(case_dir, app, args, np);
  const int rc = p.wait();
  if (rc != 0)
    throw RunError(app + " failed (exit " + std::to_string(rc) + "), see " + p.log_path() + ":" +
                   log_tail(p.log_path()));
  return p.times();
}

}  // namespace scene
