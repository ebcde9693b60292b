#include "granular/flow_replica.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "scene/cli.hpp"
#include "scene/io.hpp"
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

ReplicaOutcome run_replica(const FlowSetup& f, const scene::Lattice& geometry, const ReplicaPlan& plan,
                           std::atomic<double>* progress) {
  FlowConfig cfg = f.config;
  cfg.seed = plan.seed;
  FlowSimulation sim(cfg);
  ReplicaOutcome out;
  const Stats s0 = sim.stats();
  out.energy_initial = s0.kinetic_energy;
  out.particles_initial = static_cast<double>(s0.particles);
  const double tau = f.flow_through_time;
  double last_reported = sim.time();
  auto advance = [&](double t) {
    sim.run_until(t);
    if (progress) progress->fetch_add(sim.time() - last_reported);
    last_reported = sim.time();
  };

  // Warm-up.
  if (plan.warmup) {
    const double t_end = sim.time() + *plan.warmup * tau;
    const double chunk = kCheckFlowThroughs * tau;
    while (sim.time() < t_end && !scene::interrupted()) advance(std::min(t_end, sim.time() + chunk));
    out.steady_detected = false;
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
      advance(step * dt);
      const double t = sim.time();
      if (!rule.add(t, static_cast<double>(sim.stats().particles))) continue;
      if (rule.steady()) {
        out.steady_detected = true;
        break;
      }
      if (t >= kMaxWarmupFlowThroughs * tau - 0.5 * dt) break;
    }
  }
  out.warmup_time = sim.time();

  // Averaging.
  const double cell = std::min(geometry.dx, geometry.dy) * f.scale;
  const double dt_sample = kSampleCellFraction * cell / f.config.inflow_speed;
  const auto snaps = std::max<long>(1, std::lround(plan.averaging * tau / dt_sample));
  const std::size_t ncell = static_cast<std::size_t>(geometry.nx) * static_cast<std::size_t>(geometry.ny);
  out.blocks.assign(static_cast<std::size_t>(plan.batches), FieldSums(ncell));
  const Binner binner(f, geometry);
  const double t0 = sim.time();
  double count_sum = 0;
  long taken = 0;
  for (long k = 0; k < snaps && !scene::interrupted(); ++k) {
    advance(t0 + static_cast<double>(k + 1) * dt_sample);
    FieldSums& block = out.blocks[static_cast<std::size_t>(k * plan.batches / snaps)];
    sim.for_each_particle([&](scene::Vec2 r, scene::Vec2 v) {
      const std::size_t c = binner.cell_of(r);
      if (c != Binner::npos) block.add(c, v);
    });
    block.end_snapshot();
    count_sum += static_cast<double>(sim.stats().particles);
    ++taken;
  }
  out.interrupted = scene::interrupted();
  out.particles_mean = taken > 0 ? count_sum / static_cast<double>(taken) : 0.0;
  out.stats = sim.stats();
  if (!plan.snapshot_path.empty()) write_particles(sim, f, plan.snapshot_path);
  return out;
}

}  // namespace granular
