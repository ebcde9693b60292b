#pragma once
// One replica of the stream: warm-up until steady (detected from the number
// of disks in the domain, or a fixed time), then averaging with regular
// snapshots binned into the lattice.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "granular/flow_fields.hpp"
#include "granular/flow_setup.hpp"

namespace granular {

struct ReplicaPlan {
  std::uint64_t seed = 1;
  int batches = 1;               // blocks this replica's averaging is split into
  std::optional<double> warmup;  // flow-through times; unset: detect
  double averaging = 3.0;        // flow-through times
  std::string snapshot_path;     // final particles as CSV when not empty
};

struct ReplicaOutcome {
  std::vector<FieldSums> blocks;
  Stats stats;                   // engine statistics at the end
  double energy_initial = 0;     // kinetic energy in the domain at t = 0
  double particles_initial = 0;
  double particles_mean = 0;     // mean disks in the domain while averaging
  double warmup_time = 0;        // engine time units
  bool steady_detected = false;
  bool interrupted = false;
};

// `progress` accumulates simulated time (engine units) for the caller's
// progress display. Polls scene::interrupted() between chunks.
ReplicaOutcome run_replica(const FlowSetup& f, const scene::Lattice& geometry, const ReplicaPlan& plan,
                           std::atomic<double>* progress);

// Steady-state test on the disk count history (equally spaced samples):
// true when the mean of the last half-window matches the mean of the one
// before within max(kSteadyRelTol, noise). Exposed for tests.
bool counts_steady(const std::vector<double>& counts, std::size_t window);

}  // namespace granular
