#pragma once
// Progress for long runs: on a terminal one self-updating stderr line with
// rate and ETA; otherwise a plain line at most every `quiet_interval_s`
// (and none at all when CI=true). Libraries never print to stdout.
#include <chrono>
#include <string>

namespace scene {

class Progress {
 public:
  Progress(std::string label, double total, std::string unit = "");
  void update(double done, const std::string& extra = "");
  void finish(const std::string& extra = "");
  ~Progress();

 private:
  std::string label_, unit_;
  double total_;
  double done_ = 0;
  bool tty_, quiet_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

// Logging to stderr, one line each (quiet when CI=true unless `always`).
void log_line(const std::string& msg, bool always = false);

}  // namespace scene
