#include "granular/flow_replica.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "scene/cli.hpp"
#include "scene/io.hpp"
#include "snapshot_binning.hpp"
#include "steady_state.hpp"

namespace granular {

namespace {

// Warm-up is at least one flow-through time: the shock grows from the body
// and the prefilled domain must be swept once before the count can settle.
constexpr double kMinWarmupFlowThroughs = 1.0;
// ... and at most this many; a flow still drifting then (a stagnation zone
// that keeps growing) is averaged anyway, with steady_detected = false.
constexpr double kMaxWarmupFlowThroughs = 8.0;
// Steady-state test cadence: a check every quarter flow-through time, on
// disk counts taken 8 times per check, comparing two half flow-through
// windows.
constexpr double kCheckFlowThroughs = 0.25;
constexpr int kCountsPerCheck = 8;
constexpr double kWindowFlowThroughs = 0.5;
// The steady test itself (window comparison, tolerances) is
// FlowSteadyState, steady_state.hpp.
// Snapshots while averaging: a disk at the inflow speed crosses about half
// a lattice cell between two, so consecutive snapshots are not redundant.
constexpr double kSampleCellFraction = 0.5;

void write_particles(const FlowSimulation& sim, const FlowSetup& f, const std::string& path) {
  scene::write_stream_atomic(path, [&](std::ostream& os) {
    os << "x,y,u,v\n";
    os.precision(9);
    sim.for_each_particle([&](scene::Vec2 r, scene::Vec2 v) {
      const scene::Vec2 q = to_scene(f, r);
      os << q.x << ',' << q.y << ',' << v.x << ',' << v.y << '\n';
    });
  });
}

}  // namespace

bool counts_steady(const std::vector<double>& counts, std::size_t window) {
  const FlowSteadyCriteria c;
  return counts_settled(counts, window, c.rel_tol, c.noise_sigmas);
}

double snapshot_interval(const FlowSetup& f, const scene::Lattice& geometry) {
  const double cell = std::min(geometry.dx, geometry.dy) * f.scale;
  return kSampleCellFraction * cell / f.config.inflow_speed;
}

namespace {

FlowConfig seeded(const FlowSetup& f, std::uint64_t seed) {
  FlowConfig cfg = f.config;
  cfg.seed = seed;
  return cfg;
}

}  // namespace

FlowReplica::FlowReplica(const FlowSetup& f, const scene::Lattice& geometry,
                         const ReplicaPlan& plan)
    : f_(&f),
      geometry_(&geometry),
      plan_(plan),
      sim_(seeded(f, plan.seed)),
      binner_(f, geometry),
      dt_sample_(snapshot_interval(f, geometry)),
      slice_snapshots_(std::max<long>(
          1, std::lround(plan.group_slice_flow_throughs * f.flow_through_time / dt_sample_))) {
  const Stats s0 = sim_.stats();
  energy_initial_ = s0.kinetic_energy;
  particles_initial_ = static_cast<double>(s0.particles);
  last_reported_ = sim_.time();
}

void FlowReplica::advance(double t, std::atomic<double>* progress) {
  sim_.run_until(t);
  if (progress) progress->fetch_add(sim_.time() - last_reported_);
  last_reported_ = sim_.time();
}

void FlowReplica::warm_up(std::atomic<double>* progress) {
  if (warmed_) return;
  warmed_ = true;
  const double tau = f_->flow_through_time;
  if (plan_.warmup) {
    const double t_end = sim_.time() + *plan_.warmup * tau;
    const double chunk = kCheckFlowThroughs * tau;
    while (sim_.time() < t_end && !scene::interrupted())
      advance(std::min(t_end, sim_.time() + chunk), progress);
    steady_detected_ = false;
  } else {
    const double dt = kCheckFlowThroughs * tau / kCountsPerCheck;
    FlowSteadyCriteria c;
    c.window = static_cast<std::size_t>(std::lround(kWindowFlowThroughs * tau / dt));
    c.check_every = static_cast<std::size_t>(kCountsPerCheck);
    c.min_time = kMinWarmupFlowThroughs * tau - 0.5 * dt;
    FlowSteadyState rule(c);
    int step = 0;
    while (!scene::interrupted()) {
      ++step;
      advance(step * dt, progress);
      const double t = sim_.time();
      if (!rule.add(t, static_cast<double>(sim_.stats().particles))) continue;
      if (rule.steady()) {
        steady_detected_ = true;
        break;
      }
      if (t >= kMaxWarmupFlowThroughs * tau - 0.5 * dt) break;
    }
  }
  warmup_time_ = sim_.time();
  t0_ = sim_.time();
}

void FlowReplica::average(long snapshots, std::atomic<double>* progress) {
  warm_up(progress);
  if (snapshots <= 0 || scene::interrupted()) return;
  const std::size_t ncell =
      static_cast<std::size_t>(geometry_->nx) * static_cast<std::size_t>(geometry_->ny);
  // Each snapshot goes to the group of its slice of the averaging, counted
  // from the end of the warm-up: the groups, and so the fields, are those
  // of one long run however the averaging is chunked.
  if (groups_.empty())
    groups_.assign(static_cast<std::size_t>(std::max(1, plan_.groups)), FieldSums(ncell));
  for (long k = 0; k < snapshots && !scene::interrupted(); ++k) {
    // Snapshot times count from the end of the warm-up over all chunks, so
    // chunked averaging samples exactly the times of one long run.
    advance(t0_ + static_cast<double>(taken_ + 1) * dt_sample_, progress);
    FieldSums& group =
        groups_[static_cast<std::size_t>(taken_ / slice_snapshots_) % groups_.size()];
    // The binning pass counts the disks: stats() would walk them a second time.
    const std::size_t disks =
        bin_snapshot(binner_, group, [this](const auto& add) { sim_.for_each_particle(add); });
    count_sum_ += static_cast<double>(disks);
    ++taken_;
  }
}

ReplicaOutcome FlowReplica::outcome() const {
  ReplicaOutcome out;
  out.groups = groups_;
  out.stats = sim_.stats();
  out.energy_initial = energy_initial_;
  out.particles_initial = particles_initial_;
  out.particles_mean = taken_ > 0 ? count_sum_ / static_cast<double>(taken_) : 0.0;
  out.warmup_time = warmup_time_;
  out.steady_detected = steady_detected_;
  out.interrupted = scene::interrupted();
  return out;
}

void FlowReplica::write_snapshot() const {
  if (!plan_.snapshot_path.empty()) write_particles(sim_, *f_, plan_.snapshot_path);
}

ReplicaOutcome run_replica(const FlowSetup& f, const scene::Lattice& geometry,
                           const ReplicaPlan& plan, std::atomic<double>* progress) {
  FlowReplica r(f, geometry, plan);
  const double tau = f.flow_through_time;
  r.average(std::max<long>(1, std::lround(plan.averaging * tau / snapshot_interval(f, geometry))),
            progress);
  const ReplicaOutcome out = r.outcome();
  r.write_snapshot();
  return out;
}

}  // namespace granular
