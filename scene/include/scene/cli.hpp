#pragma once
// Shared executable plumbing: Ctrl-C handling and the exit-code contract.
#include <functional>
#include <string>

namespace scene {

// SIGINT (or SIGTERM) sets a flag that long loops poll; a second one aborts
// at once. A process that has not stopped `grace_seconds` after the first
// (stuck in a call that polls nothing) is stopped by a watchdog with one
// line on stderr and exit code 130; whatever it had staged stays where it is.
constexpr unsigned kInterruptGraceSeconds = 30;
void install_interrupt_handler(unsigned grace_seconds = kInterruptGraceSeconds);
bool interrupted();
void clear_interrupt();  // tests

// The contract's one line: a newline becomes "\\n" and other control
// characters '?', so a file name or YAML value cannot split the message.
std::string one_line(const std::string& msg);

// Runs `body`, turning exceptions into one "PROGRAM: error: ..." line on
// stderr and the contract's exit codes (InputError 2, RunError 1, other 1).
int run_guarded(const std::string& program, const std::function<int()>& body);

// The release number and a hash of the sources it was built from
// (e.g. 0.1.0+3f9a0c1b2d4e): caches made by other code are never reused.
std::string version_string();

}  // namespace scene
