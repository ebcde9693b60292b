#pragma once
// One replica of the stream: warm-up until steady (detected from the number
// of disks in the domain, or a fixed time), then averaging with regular
// snapshots binned into the lattice. A FlowReplica keeps its simulation
// between calls, so the averaging can go on in chunks (precision on demand)
// with the same snapshots, at the same times, as one uninterrupted run.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "granular/engine.hpp"
#include "granular/flow_fields.hpp"
#include "granular/flow_setup.hpp"

namespace granular {

struct ReplicaPlan {
  std::uint64_t seed = 1;
  // Averaging groups (the shock's interval): consecutive slices of the averaging (counted from the
  // end of the warm-up, whatever the chunks) dealt in turn into this many
  // groups, so that a group's sums do not depend on how the run was chunked.
  int groups = 1;
  double group_slice_flow_throughs = 0.25;
  std::optional<double> warmup;  // flow-through times; unset: detect
  double averaging = 3.0;        // flow-through times
  std::string snapshot_path;     // final particles as CSV when not empty
};

struct ReplicaOutcome {
  std::vector<FieldSums> groups;  // plan.groups averaging groups (empty before averaging)
  Stats stats;                   // engine statistics at the end
  double energy_initial = 0;     // kinetic energy in the domain at t = 0
  double particles_initial = 0;
  double particles_mean = 0;     // mean disks in the domain while averaging
  double warmup_time = 0;        // engine time units
  bool steady_detected = false;
  bool interrupted = false;
};

// Engine time between two averaging snapshots: a disk at the inflow speed
// crosses about half a lattice cell.
double snapshot_interval(const FlowSetup& f, const scene::Lattice& geometry);

class FlowReplica {
 public:
  // Builds the replica's simulation (prefilled domain, seed plan.seed).
  // plan.averaging is not used: the caller asks for snapshots.
  FlowReplica(const FlowSetup& f, const scene::Lattice& geometry, const ReplicaPlan& plan);
  // Warm-up (plan.warmup, or until steady); once only, before average().
  void warm_up(std::atomic<double>* progress);
  // `snapshots` more averaging snapshots (one chunk), each binned into the
  // group of its slice.
  void average(long snapshots, std::atomic<double>* progress);
  // Everything so far.
  ReplicaOutcome outcome() const;
  // Final particles to plan.snapshot_path, when set.
  void write_snapshot() const;

 private:
  const FlowSetup* f_;
  const scene::Lattice* geometry_;
  ReplicaPlan plan_;
  FlowSimulation sim_;
  Binner binner_;
  double dt_sample_ = 0, t0_ = 0, last_reported_ = 0;
  long taken_ = 0;
  double count_sum_ = 0, energy_initial_ = 0, particles_initial_ = 0, warmup_time_ = 0;
  bool steady_detected_ = false, warmed_ = false;
  std::vector<FieldSums> groups_;  // plan.groups, filled slice by slice
  long slice_snapshots_ = 1;

  void advance(double t, std::atomic<double>* progress);
};

// One uninterrupted run: warm-up, then plan.averaging flow-through times.
// `progress` accumulates simulated time (engine units) for the caller's
// progress display. Polls scene::interrupted() between chunks.
ReplicaOutcome run_replica(const FlowSetup& f, const scene::Lattice& geometry, const ReplicaPlan& plan,
                           std::atomic<double>* progress);

// Steady-state test on the disk count history (equally spaced samples):
// true when the mean of the last half-window matches the mean of the one
// before within max(kSteadyRelTol, noise). Exposed for tests.
bool counts_steady(const std::vector<double>& counts, std::size_t window);

}  // namespace granular
