#include "scene/process.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "scene/errors.hpp"

namespace scene {

namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double seconds_of(const timeval& t) {
  constexpr double kMicro = 1e-6;
  return static_cast<double>(t.tv_sec) + kMicro * static_cast<double>(t.tv_usec);
}

int code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  constexpr int kSignalBase = 128;  // the shell's convention for a killed child
  return WIFSIGNALED(status) ? kSignalBase + WTERMSIG(status) : kSignalBase;
}

// What the child reports through the close-on-exec pipe when it cannot exec:
// the step that failed and errno. Nothing arrives when exec succeeds.
struct StartFailure {
  int step = 0;
  int error = 0;
};
constexpr int kStepLog = 1, kStepStdin = 2, kStepWorkDir = 3, kStepExec = 4;
// Exit status of a child that could not exec (as the shell's "not found").
constexpr int kCannotExec = 127;

[[noreturn]] void child_fail(int fd, int step) {
  const StartFailure f{step, errno};
  // Best effort: the parent treats a short read as a plain exec failure.
  [[maybe_unused]] const ssize_t n = ::write(fd, &f, sizeof f);
  ::_exit(kCannotExec);
}

std::string step_name(int step) {
  switch (step) {
    case kStepLog:
      return "cannot open its log";
    case kStepStdin:
      return "cannot open /dev/null";
    case kStepWorkDir:
      return "cannot enter its working directory";
    default:
      return "exec failed";
  }
}

}  // namespace

std::string find_program(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0 ? name : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::string p = dir + "/" + name;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return "";
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const ChildOptions& options)
    : log_(options.log_path), program_(argv.empty() ? std::string() : argv.front()) {
  if (argv.empty()) throw RunError("cannot start a program: empty command");
  const std::string exe = find_program(argv.front());
  if (exe.empty()) throw RunError("cannot start " + argv.front() + ": not found on PATH");
  // Everything the child needs is prepared here: between fork and exec only
  // async-signal-safe calls are allowed.
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string log = options.log_path.empty() ? std::string("/dev/null") : options.log_path;
  const std::string& work_dir = options.work_dir;

  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0)
    throw RunError("cannot start " + argv.front() + ": pipe failed");
  const pid_t parent = ::getpid();
  started_ = now_seconds();
  pid_ = ::fork();
  if (pid_ < 0) {
    ::close(report[0]);
    ::close(report[1]);
    throw RunError("cannot start " + argv.front() + ": fork failed");
  }
  if (pid_ == 0) {
    ::close(report[0]);
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(kCannotExec);  // the parent died before prctl
    const int in = ::open("/dev/null", O_RDONLY);
    if (in < 0 || ::dup2(in, STDIN_FILENO) < 0) child_fail(report[1], kStepStdin);
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || ::dup2(out, STDOUT_FILENO) < 0 || ::dup2(out, STDERR_FILENO) < 0)
      child_fail(report[1], kStepLog);
    if (!work_dir.empty() && ::chdir(work_dir.c_str()) != 0) child_fail(report[1], kStepWorkDir);
    ::execv(exe.c_str(), args.data());
    child_fail(report[1], kStepExec);
  }
  // Also here: whichever of parent and child runs first, the group exists
  // before anyone signals it.
  ::setpgid(pid_, pid_);
  ::close(report[1]);
  StartFailure f;
  ssize_t n = 0;
  do {
    n = ::read(report[0], &f, sizeof f);
  } while (n < 0 && errno == EINTR);
  ::close(report[0]);
  if (n > 0) {
    wait();
    const std::string where = f.step == kStepLog       ? " " + log
                              : f.step == kStepWorkDir ? " " + work_dir
                                                       : "";
    throw RunError("cannot start " + argv.front() + ": " + step_name(f.step) + where + ": " +
                   std::strerror(f.error));
  }
}

ChildProcess::~ChildProcess() {
  if (!done_ && pid_ > 0) {
    terminate();
    wait();
  }
}

bool ChildProcess::reap(int flags) {
  int status = 0;
  rusage usage{};
  pid_t r = 0;
  do {
    r = ::wait4(pid_, &status, flags, &usage);
  } while (r < 0 && errno == EINTR);
  if (r == 0) return false;  // WNOHANG and still running
  done_ = true;
  times_.wall_seconds = now_seconds() - started_;
  if (r < 0) {
    code_ = -1;
    return true;
  }
  code_ = code_of(status);
  // wait4 reports the child's own usage plus that of every descendant it
  // reaped itself (RUSAGE_CHILDREN of the child), so mpirun's ranks count.
  times_.cpu_seconds = seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
  return true;
}

bool ChildProcess::poll() {
  return done_ || reap(WNOHANG);
}

int ChildProcess::wait() {
  if (!done_) reap(0);
  return code_;
}

void ChildProcess::terminate() {
  if (!done_ && pid_ > 0) ::kill(-pid_, SIGTERM);
}

ChildTimes run_child(const std::vector<std::string>& argv, const ChildOptions& options) {
  ChildProcess p(argv, options);
  const int rc = p.wait();
  if (rc != 0)
    throw RunError(argv.front() + " failed (exit " + std::to_string(rc) + ")" +
                   (options.log_path.empty() ? std::string() : ", see " + options.log_path));
  return p.times();
}

std::string log_tail(const std::string& path, int lines) {
  std::ifstream in(path);
  if (!in) return "(no log)";
  std::vector<std::string> all;
  std::string l;
  while (std::getline(in, l))
    if (!l.empty()) all.push_back(l);
  const auto keep = static_cast<std::size_t>(lines > 0 ? lines : 0);
  const std::size_t from = all.size() > keep ? all.size() - keep : 0;
  std::ostringstream o;
  for (std::size_t k = from; k < all.size(); ++k) o << "\n    " << all[k];
  return o.str();
}

}  // namespace scene
