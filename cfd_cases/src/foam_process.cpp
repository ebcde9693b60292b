#include "foam_process.hpp"

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "scene/errors.hpp"

namespace cfd {
namespace fs = std::filesystem;

namespace {
constexpr const char* kDefaultBashrc = "/usr/share/openfoam/etc/bashrc";

std::string quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string foam_bashrc() {
  std::vector<std::string> candidates;
  if (const char* e = std::getenv("SHOCKGRAIN_FOAM_BASHRC")) candidates.emplace_back(e);
  if (const char* e = std::getenv("WM_PROJECT_DIR")) candidates.push_back(std::string(e) + "/etc/bashrc");
  candidates.emplace_back(kDefaultBashrc);
  for (const auto& c : candidates)
    if (fs::exists(c)) return c;
  throw scene::RunError(std::string("OpenFOAM environment not found (tried $SHOCKGRAIN_FOAM_BASHRC, "
                                    "$WM_PROJECT_DIR/etc/bashrc, ") + kDefaultBashrc + ")");
}

std::string foam_command(const std::string& app, const std::string& args, int np) {
  std::string cmd;
  if (np > 1) {
    // --oversubscribe: more ranks than cores is fine for small cases; root
    // needs --allow-run-as-root (containers, CI).
    cmd = "mpirun -np " + std::to_string(np) + " --oversubscribe" +
          (geteuid() == 0 ? " --allow-run-as-root" : "") + " " + app + " -parallel";
  } else {
    cmd = app;
  }
  if (!args.empty()) cmd += " " + args;
  return cmd + " > log." + app + " 2>&1";
}

FoamProcess::FoamProcess(const std::string& case_dir, const std::string& app, const std::string& args, int np)
    : log_(case_dir + "/log." + app) {
  const std::string script = ". " + quote(foam_bashrc()) + " > /dev/null 2>&1; cd " + quote(case_dir) +
                             " || exit 97; exec " + foam_command(app, args, np);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw scene::RunError("cannot start " + app + ": fork failed");
  if (pid_ == 0) {
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(98);
    execl("/bin/bash", "bash", "-c", script.c_str(), static_cast<char*>(nullptr));
    _exit(99);
  }
  setpgid(pid_, pid_);
}

FoamProcess::~FoamProcess() {
  if (!done_ && pid_ > 0) {
    terminate();
    wait();
  }
}

bool FoamProcess::poll() {
  if (done_) return true;
  int status = 0;
  const pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == 0) return false;
  done_ = true;
  code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return true;
}

int FoamProcess::wait() {
  if (done_) return code_;
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0) {
    if (errno != EINTR) {
      done_ = true;
      code_ = -1;
      return code_;
    }
  }
  done_ = true;
  code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return code_;
}

void FoamProcess::terminate() {
  if (!done_ && pid_ > 0) kill(-pid_, SIGTERM);
}

std::string log_tail(const std::string& path, int lines) {
  std::ifstream in(path);
  if (!in) return "(no log)";
  std::vector<std::string> all;
  std::string l;
  while (std::getline(in, l)) all.push_back(l);
  std::ostringstream o;
  const std::size_t from = all.size() > static_cast<std::size_t>(lines) ? all.size() - static_cast<std::size_t>(lines) : 0;
  for (std::size_t k = from; k < all.size(); ++k)
    if (!all[k].empty()) o << "\n    " << all[k];
  return o.str();
}

void run_foam(const std::string& case_dir, const std::string& app, const std::string& args, int np) {
  FoamProcess p(case_dir, app, args, np);
  const int rc = p.wait();
  if (rc != 0)
    throw scene::RunError(app + " failed (exit " + std::to_string(rc) + "), see " + p.log_path() + ":" +
                          log_tail(p.log_path()));
}

}  // namespace cfd
