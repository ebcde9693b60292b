#pragma once
// The granular stream's steady-state rule, as a value: feed it the number of
// disks in the domain at equally spaced times and ask whether the stream is
// steady and why. A stream past a body is steady once the disk count has
// stopped drifting: the shock has grown to its size and the prefilled domain
// has been swept out.
#include <cstddef>
#include <string>
#include <vector>

namespace granular {

struct FlowSteadyCriteria {
  std::size_t window = 0;       // samples per window; two windows are compared
  std::size_t check_every = 1;  // samples between checks
  double min_time = 0.0;        // engine time before a check may pass
  // Two windows whose mean counts differ by less than rel_tol of the latest
  // (or by less than noise_sigmas of their own counting noise, for small
  // systems) count as steady.
  double rel_tol = 0.02;
  double noise_sigmas = 2.0;
};

class FlowSteadyState {
 public:
  explicit FlowSteadyState(FlowSteadyCriteria c) : c_(c) {}

  // Appends the disk count sampled at engine time `time`. A check runs every
  // check_every samples once time >= min_time; returns whether this sample
  // was checked. Once steady, stays steady.
  bool add(double time, double count);

  bool steady() const { return steady_; }
  const std::string& why() const { return why_; }
  const std::vector<double>& counts() const { return counts_; }

 private:
  FlowSteadyCriteria c_;
  std::vector<double> counts_;
  bool steady_ = false;
  std::string why_ = "no samples yet";
};

// The window test alone: true when the mean of the last window matches the
// mean of the one before within max(rel_tol * latest, noise).
bool counts_settled(const std::vector<double>& counts, std::size_t window, double rel_tol,
                    double noise_sigmas);

}  // namespace granular
