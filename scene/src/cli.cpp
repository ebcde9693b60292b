#include "scene/cli.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "scene/errors.hpp"
#include "code_hash.hpp"
#include "version.hpp"

namespace scene {

namespace {
// A signal handler can only reach process-wide state: this flag is the one
// deliberate global of the project.
volatile std::sig_atomic_t g_interrupts = 0;

extern "C" void on_sigint(int) {
  g_interrupts = g_interrupts + 1;
  if (g_interrupts >= 2) std::_Exit(130);  // second Ctrl-C: stop now
}
}  // namespace

void install_interrupt_handler() { std::signal(SIGINT, on_sigint); std::signal(SIGTERM, on_sigint); }
bool interrupted() { return g_interrupts != 0; }
void clear_interrupt() { g_interrupts = 0; }

namespace {
// The contract's one line: a file name or YAML value holding a newline (or
// other control character) must not split the message.
std::string one_line(const std::string& msg) {
  std::string out;
  out.reserve(msg.size());
  for (const char c : msg) {
    if (c == '\n') out += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += '?';
    else out += c;
  }
  return out;
}
}  // namespace

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

std::string version_string() { return std::string(kVersion) + "+" + kCodeHash; }

}  // namespace scene
