#include "scene/progress.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <unistd.h>

#include "scene/units.hpp"

namespace scene {

namespace {
// Seconds between plain progress lines when stderr is not a terminal.
constexpr double kPlainInterval = 30.0;
// Seconds between redraws on a terminal.
constexpr double kTtyInterval = 0.2;

bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string_view(ci) != "" && std::string_view(ci) != "false" && std::string_view(ci) != "0";
}

std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--";
  char buf[32];
  const long t = std::lround(s);
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}
}  // namespace

Progress::Progress(std::string label, double total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total),
      tty_(::isatty(STDERR_FILENO) != 0), quiet_(in_ci()),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(double done, const std::string& extra) {
  done_ = done;
  // Work that grew on the way (grids run again after a divergence) ends the
  // count at 100% rather than past it with a negative ETA.
  if (total_ > 0 && done > total_) total_ = done;
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (since < (tty_ ? kTtyInterval : kPlainInterval)) return;
  last_ = now;
  const double el = std::chrono::duration<double>(now - start_).count();
  const double rate = el > 0 ? done / el : 0.0;
  const double eta = rate > 0 && total_ > 0 ? (total_ - done) / rate : kNaN;
  const double pct = total_ > 0 ? 100.0 * done / total_ : 0.0;
  std::fprintf(stderr, "%s%s: %5.1f%%  %.3g %s/s  elapsed %s  ETA %s  %s%s", tty_ ? "\r\033[K" : "",
               label_.c_str(), pct, rate, unit_.c_str(), hms(el).c_str(), hms(eta).c_str(),
               extra.c_str(), tty_ ? "" : "\n");
  std::fflush(stderr);
}

void Progress::finish(const std::string& extra) {
  if (finished_) return;
  finished_ = true;
  if (quiet_) return;
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s: done in %s  %s\n", tty_ ? "\r\033[K" : "", label_.c_str(), hms(el).c_str(),
               extra.c_str());
}

Progress::~Progress() {
  if (tty_ && !finished_ && !quiet_) std::fprintf(stderr, "\n");
}

void log_line(const std::string& msg, bool always) {
  if (!always && in_ci()) return;
  std::fprintf(stderr, "%s\n", msg.c_str());
}

}  // namespace scene
