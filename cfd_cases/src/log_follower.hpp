#pragma once
// Follows a growing solver log: the time of every step ("Time = t" lines)
// and signs of divergence printed before any field is written.
#include <cstdint>
#include <string>
#include <vector>

namespace cfd {

class LogFollower {
 public:
  explicit LogFollower(std::string path) : path_(std::move(path)) {}
  void update();  // reads what was appended since the last call
  double last_time() const { return times_.empty() ? -1.0 : times_.back(); }
  long steps() const { return static_cast<long>(times_.size()); }
  long steps_upto(double t) const;  // steps whose time is <= t (with round-off slack)
  bool diverged() const { return !divergence_.empty(); }
  const std::string& divergence() const { return divergence_; }

 private:
  std::string path_;
  std::uint64_t offset_ = 0;
  std::string partial_;
  std::vector<double> times_;
  std::string divergence_;
};

}  // namespace cfd
