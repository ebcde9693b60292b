#include "scene/cli.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "code_hash.hpp"
#include "scene/errors.hpp"
#include "version.hpp"

namespace scene {

namespace {
// A signal handler can only reach process-wide state: these are the
// deliberate globals of the project.
volatile std::sig_atomic_t g_interrupts = 0;
volatile std::sig_atomic_t g_grace_seconds = kInterruptGraceSeconds;

extern "C" void on_sigint(int) {
  g_interrupts = g_interrupts + 1;
  if (g_interrupts >= 2) std::_Exit(130);  // second Ctrl-C: stop now
  // The watchdog: alarm() is async-signal-safe and needs no thread.
  alarm(static_cast<unsigned>(g_grace_seconds));
}

extern "C" void on_watchdog(int) {
  if (g_interrupts == 0) return;  // an alarm nobody here asked for
  static constexpr char kMsg[] =
      "interrupted: the process did not stop within its grace period after the signal; exiting "
      "now\n";
  // write(2), not stdio: the only output that is safe inside a handler.
  [[maybe_unused]] const auto n = write(STDERR_FILENO, kMsg, sizeof kMsg - 1);
  std::_Exit(130);
}
}  // namespace

void install_interrupt_handler(unsigned grace_seconds) {
  g_grace_seconds = static_cast<std::sig_atomic_t>(grace_seconds);
  std::signal(SIGALRM, on_watchdog);
  std::signal(SIGINT, on_sigint);
  std::signal(SIGTERM, on_sigint);
}
bool interrupted() {
  return g_interrupts != 0;
}
void clear_interrupt() {
  g_interrupts = 0;
  alarm(0);
}

std::string one_line(const std::string& msg) {
  std::string out;
  out.reserve(msg.size());
  for (const char c : msg) {
    if (c == '\n')
      out += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += '?';
    else
      out += c;
  }
  return out;
}

int run_guarded(const std::string& program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), one_line(e.what()).c_str());
    return 2;
  } catch (const RunError& e) {
    std::fprintf(stderr, "%s: run failed: %s\n", program.c_str(), one_line(e.what()).c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: run failed: out of memory\n", program.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: run failed: %s\n", program.c_str(), one_line(e.what()).c_str());
    return 1;
  }
}

std::string version_string() {
  return std::string(kVersion) + "+" + kCodeHash;
}

}  // namespace scene
