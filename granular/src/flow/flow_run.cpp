#include "granular/flow_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "granular/flow_fields.hpp"
#include "granular/flow_replica.hpp"
#include "granular/flow_setup.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace granular {

namespace {

// With a single replica the spread between replicas is unknown; the
// averaging is then cut into this many consecutive batches instead (batch
// means, slightly optimistic because neighbouring batches correlate).
constexpr int kSingleReplicaBatches = 4;
// Warm-up assumed for the progress estimate when it is detected.
constexpr double kWarmupGuessFlowThroughs = 2.0;
constexpr auto kProgressPoll = std::chrono::milliseconds(50);

// Per-replica scalars travel with the field sums in one vector so that one
// element-wise sum over ranks reduces everything.
enum Slot : std::size_t {
  present, collisions, disk_collisions, wall_collisions, recoveries, inserted, removed, max_overlap,
  energy_final, particles_final, time_final, energy_initial, particles_initial, particles_mean,
  warmup_time, steady, interrupted_flag, kSlots
};

std::vector<double> pack(const ReplicaOutcome& r) {
  std::vector<double> v(kSlots, 0.0);
  v[present] = 1;
  v[collisions] = static_cast<double>(r.stats.collisions);
  v[disk_collisions] = static_cast<double>(r.stats.disk_collisions);
  v[wall_collisions] = static_cast<double>(r.stats.wall_collisions);
  v[recoveries] = static_cast<double>(r.stats.recoveries);
  v[inserted] = static_cast<double>(r.stats.inserted);
  v[removed] = static_cast<double>(r.stats.removed);
  v[max_overlap] = r.stats.max_overlap;
  v[energy_final] = r.stats.kinetic_energy;
  v[particles_final] = static_cast<double>(r.stats.particles);
  v[time_final] = r.stats.time;
  v[energy_initial] = r.energy_initial;
  v[particles_initial] = r.particles_initial;
  v[particles_mean] = r.particles_mean;
  v[warmup_time] = r.warmup_time;
  v[steady] = r.steady_detected ? 1 : 0;
  v[interrupted_flag] = r.interrupted ? 1 : 0;
  for (const FieldSums& b : r.blocks) v.insert(v.end(), b.raw().begin(), b.raw().end());
  return v;
}

// Where each replica's numbers sit in the vector summed over ranks: kSlots
// scalars, then `batches` blocks of field sums.
struct Layout {
  int replicas = 1;
  int batches = 1;
  std::size_t ncell = 0, block_size = 0, stride = 0;
};

Layout layout_for(const scene::GranularParams& p, const scene::Lattice& geometry) {
  Layout l;
  l.replicas = p.replicas;
  l.batches = l.replicas == 1 ? kSingleReplicaBatches : 1;
  l.ncell = static_cast<std::size_t>(geometry.nx) * static_cast<std::size_t>(geometry.ny);
  l.block_size = FieldSums(l.ncell).raw().size();
  l.stride = kSlots + static_cast<std::size_t>(l.batches) * l.block_size;
  return l;
}

// The replicas this member of the group runs: replica i on rank i % size.
std::vector<int> replicas_of(const ReplicaGroup& group, int replicas) {
  std::vector<int> mine;
  for (int i = 0; i < replicas; ++i)
    if (i % std::max(1, group.size) == group.rank) mine.push_back(i);
  return mine;
}

// Runs this member's replicas in o.np threads, each packing its outcome into
// its stride of `all`; the calling thread only shows progress (on rank 0).
// A failure anywhere is rethrown on every rank. Returns the thread count.
int run_replicas(const scene::Scene& s, const FlowSetup& f, const scene::Lattice& geometry,
                 const RunOptions& o, const ReplicaGroup& group, const Layout& l,
                 const std::vector<int>& mine, std::vector<double>& all) {
  const scene::GranularParams& p = s.granular;
  std::atomic<double> progress{0.0};
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  auto worker = [&]() {
    for (std::size_t k = next++; k < mine.size(); k = next++) {
      const int i = mine[k];
      try {
        ReplicaPlan plan;
        plan.seed = p.seed + static_cast<std::uint64_t>(i);
        plan.batches = l.batches;
        plan.warmup = p.warmup;
        plan.averaging = p.averaging;
        if (p.snapshots && !o.out_dir.empty())
          plan.snapshot_path = o.out_dir + "/snapshots/replica_" + std::to_string(i) + ".csv";
        const std::vector<double> v = pack(run_replica(f, geometry, plan, &progress));
        std::copy(
            v.begin(), v.end(),
            all.begin() + static_cast<std::ptrdiff_t>(l.stride * static_cast<std::size_t>(i)));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  const int nthreads = std::max(1, std::min(o.np, static_cast<int>(mine.size())));
  {
    std::atomic<int> running{nthreads};
    std::vector<std::thread> threads;
    for (int t = 0; t < nthreads; ++t)
      threads.emplace_back([&]() {
        worker();
        --running;
      });
    if (group.rank == 0) {
      const double guess = (p.warmup.value_or(kWarmupGuessFlowThroughs) + p.averaging) * f.flow_through_time;
      scene::Progress bar("granular " + s.name, guess * static_cast<double>(mine.size()), "t");
      while (running.load() > 0) {
        bar.update(progress.load());
        std::this_thread::sleep_for(kProgressPoll);
      }
      bar.finish();
    }
    for (auto& t : threads) t.join();
  }
  const bool failed_here = static_cast<bool>(failure);
  const bool failed_any = group.any ? group.any(failed_here) : failed_here;
  if (failure) std::rethrow_exception(failure);
  if (failed_any) throw scene::RunError("a replica failed on another rank");
  return nthreads;
}

// The replicas' outcomes combined: counters summed, energies and particle
// counts averaged, field blocks that hold snapshots kept for averaging.
struct Combined {
  std::vector<FieldSums> blocks;
  nlohmann::json per_replica = nlohmann::json::array();
  double coll = 0, disk = 0, wall = 0, rec = 0, ins = 0, rem = 0, overlap = 0, e0 = 0, e1 = 0,
         n0 = 0, nmean = 0, warm = 0, sim_time = 0;
  bool steady_all = true, interrupted = false;
};

Combined combine(const std::vector<double>& all, const Layout& l, std::uint64_t seed) {
  Combined c;
  const int replicas = l.replicas;
  for (int i = 0; i < replicas; ++i) {
    const double* v = all.data() + l.stride * static_cast<std::size_t>(i);
    c.coll += v[collisions];
    c.disk += v[disk_collisions];
    c.wall += v[wall_collisions];
    c.rec += v[recoveries];
    c.ins += v[inserted];
    c.rem += v[removed];
    c.overlap = std::max(c.overlap, v[max_overlap]);
    c.e0 += v[energy_initial] / replicas;
    c.e1 += v[energy_final] / replicas;
    c.n0 += v[particles_initial] / replicas;
    c.nmean += v[particles_mean] / replicas;
    c.warm = std::max(c.warm, v[warmup_time]);
    c.sim_time = std::max(c.sim_time, v[time_final]);
    c.steady_all = c.steady_all && v[steady] > 0.5;
    c.interrupted = c.interrupted || v[interrupted_flag] > 0.5 || v[present] < 0.5;
    for (int b = 0; b < l.batches; ++b) {
      FieldSums fs(l.ncell);
      const double* src = v + kSlots + static_cast<std::size_t>(b) * l.block_size;
      std::copy(src, src + l.block_size, fs.raw().begin());
      if (fs.snapshots() > 0) c.blocks.push_back(std::move(fs));
    }
    c.per_replica.push_back({{"seed", seed + static_cast<std::uint64_t>(i)},
                             {"collisions", v[collisions]},
                             {"warmup_time", v[warmup_time]},
                             {"steady_detected", v[steady] > 0.5},
                             {"particles_mean", v[particles_mean]}});
  }
  return c;
}

nlohmann::json flow_summary(const scene::Scene& s, const FlowSetup& f,
                            const scene::Lattice& geometry, const Combined& c, double wall_seconds,
                            int ranks, int nthreads) {
  const scene::GranularParams& p = s.granular;
  return {
      {"kind", "flow"},
      {"scene", s.name},
      {"particles", c.nmean},
      {"particles_initial", c.n0},
      {"collisions", c.coll},
      {"disk_collisions", c.disk},
      {"wall_collisions", c.wall},
      {"recoveries", c.rec},
      {"inserted", c.ins},
      {"removed", c.rem},
      {"wall_seconds", wall_seconds},
      {"collisions_per_second", wall_seconds > 0 ? c.coll / wall_seconds : 0.0},
      {"energy_initial", c.e0},
      {"energy_final", c.e1},
      {"max_overlap", c.overlap},
      {"packing_fraction", f.packing_fraction},
      {"compressibility_factor", nullptr},
      {"temperature", f.config.temperature},
      {"replicas", p.replicas},
      {"ranks", ranks},
      {"threads", nthreads},
      {"mach", f.mach},
      {"inflow_speed", f.config.inflow_speed},
      {"sound_speed", f.sound_speed},
      {"restitution", f.config.restitution},
      {"body_diameters", f.body.length * f.scale},
      {"flow_through_time", f.flow_through_time},
      {"warmup_time", c.warm},
      {"warmup_flow_throughs", c.warm / f.flow_through_time},
      {"steady_detected", c.steady_all},
      {"averaging_time", p.averaging * f.flow_through_time},
      {"simulated_time", c.sim_time},
      {"lattice", {{"nx", geometry.nx}, {"ny", geometry.ny}}},
      {"interrupted", c.interrupted},
      {"partial", c.interrupted},  // averaged over less than the requested time
      {"flow", describe(f)},
      {"per_replica", c.per_replica},
  };
}

}  // namespace

FlowResult run_flow_scene(const scene::Scene& s, const RunOptions& o, const ReplicaGroup& group) {
  const auto wall_start = std::chrono::steady_clock::now();
  const FlowSetup f = make_flow_setup(s);
  const scene::GranularParams& p = s.granular;
  const scene::Lattice geometry = flow_lattice(f, p.lattice_nx, p.lattice_ny);
  const Layout l = layout_for(p, geometry);
  if (!o.out_dir.empty()) scene::make_dirs(o.out_dir);
  if (p.snapshots && !o.out_dir.empty()) scene::make_dirs(o.out_dir + "/snapshots");

  std::vector<double> all(l.stride * static_cast<std::size_t>(l.replicas), 0.0);
  const int nthreads =
      run_replicas(s, f, geometry, o, group, l, replicas_of(group, l.replicas), all);
  if (group.sum && group.size > 1) group.sum(all);

  const Combined c = combine(all, l, p.seed);
  if (c.blocks.empty())
    throw scene::RunError(
        c.interrupted ? "interrupted during warm-up: no fields averaged yet, nothing written"
                      : "no snapshots were averaged");
  FlowResult r;
  r.fields = make_fields(f, geometry, c.blocks);
  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.summary = flow_summary(s, f, geometry, c, wall_seconds, group.size, nthreads);
  if (group.rank == 0 && !o.out_dir.empty()) {
    scene::write_vti(r.fields, o.out_dir + "/fields.vti");
    scene::write_json_atomic(o.out_dir + "/summary.json", r.summary);
  }
  return r;
}

}  // namespace granular
