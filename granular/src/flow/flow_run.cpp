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

}  // namespace

FlowResult run_flow_scene(const scene::Scene& s, const RunOptions& o, const ReplicaGroup& group) {
  const auto wall_start = std::chrono::steady_clock::now();
  const FlowSetup f = make_flow_setup(s);
  const scene::GranularParams& p = s.granular;
  const scene::Lattice geometry = flow_lattice(f, p.lattice_nx, p.lattice_ny);
  const int replicas = p.replicas;
  const int batches = replicas == 1 ? kSingleReplicaBatches : 1;
  const std::size_t ncell = static_cast<std::size_t>(geometry.nx) * static_cast<std::size_t>(geometry.ny);
  const std::size_t block_size = FieldSums(ncell).raw().size();
  const std::size_t stride = kSlots + static_cast<std::size_t>(batches) * block_size;
  const bool root = group.rank == 0;
  if (!o.out_dir.empty()) scene::make_dirs(o.out_dir);
  if (p.snapshots && !o.out_dir.empty()) scene::make_dirs(o.out_dir + "/snapshots");

  std::vector<int> mine;
  for (int i = 0; i < replicas; ++i)
    if (i % std::max(1, group.size) == group.rank) mine.push_back(i);
  std::vector<double> all(stride * static_cast<std::size_t>(replicas), 0.0);

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
        plan.batches = batches;
        plan.warmup = p.warmup;
        plan.averaging = p.averaging;
        if (p.snapshots && !o.out_dir.empty())
          plan.snapshot_path = o.out_dir + "/snapshots/replica_" + std::to_string(i) + ".csv";
        const std::vector<double> v = pack(run_replica(f, geometry, plan, &progress));
        std::copy(v.begin(), v.end(), all.begin() + static_cast<std::ptrdiff_t>(stride * static_cast<std::size_t>(i)));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  const int nthreads = std::max(1, std::min(o.np, static_cast<int>(mine.size())));
  {
    // Workers run the replicas; the calling thread only shows progress.
    std::atomic<int> running{nthreads};
    std::vector<std::thread> threads;
    for (int t = 0; t < nthreads; ++t)
      threads.emplace_back([&]() {
        worker();
        --running;
      });
    if (root) {
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
  if (group.sum && group.size > 1) group.sum(all);

  // Unpack.
  std::vector<FieldSums> blocks;
  nlohmann::json per_replica = nlohmann::json::array();
  double coll = 0, disk = 0, wall = 0, rec = 0, ins = 0, rem = 0, overlap = 0, e0 = 0, e1 = 0, n0 = 0, nmean = 0,
         warm = 0, sim_time = 0;
  bool steady_all = true, interrupted = false;
  for (int i = 0; i < replicas; ++i) {
    const double* v = all.data() + stride * static_cast<std::size_t>(i);
    coll += v[collisions];
    disk += v[disk_collisions];
    wall += v[wall_collisions];
    rec += v[recoveries];
    ins += v[inserted];
    rem += v[removed];
    overlap = std::max(overlap, v[max_overlap]);
    e0 += v[energy_initial] / replicas;
    e1 += v[energy_final] / replicas;
    n0 += v[particles_initial] / replicas;
    nmean += v[particles_mean] / replicas;
    warm = std::max(warm, v[warmup_time]);
    sim_time = std::max(sim_time, v[time_final]);
    steady_all = steady_all && v[steady] > 0.5;
    interrupted = interrupted || v[interrupted_flag] > 0.5 || v[present] < 0.5;
    for (int b = 0; b < batches; ++b) {
      FieldSums fs(ncell);
      const double* src = v + kSlots + static_cast<std::size_t>(b) * block_size;
      std::copy(src, src + block_size, fs.raw().begin());
      if (fs.snapshots() > 0) blocks.push_back(std::move(fs));
    }
    per_replica.push_back({{"seed", p.seed + static_cast<std::uint64_t>(i)},
                           {"collisions", v[collisions]},
                           {"warmup_time", v[warmup_time]},
                           {"steady_detected", v[steady] > 0.5},
                           {"particles_mean", v[particles_mean]}});
  }
  if (blocks.empty())
    throw scene::RunError(interrupted ? "interrupted during warm-up: no fields averaged yet, nothing written"
                                      : "no snapshots were averaged");

  FlowResult r;
  r.fields = make_fields(f, geometry, blocks);
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  nlohmann::json j = {
      {"kind", "flow"},
      {"scene", s.name},
      {"particles", nmean},
      {"particles_initial", n0},
      {"collisions", coll},
      {"disk_collisions", disk},
      {"wall_collisions", wall},
      {"recoveries", rec},
      {"inserted", ins},
      {"removed", rem},
      {"wall_seconds", wall_seconds},
      {"collisions_per_second", wall_seconds > 0 ? coll / wall_seconds : 0.0},
      {"energy_initial", e0},
      {"energy_final", e1},
      {"max_overlap", overlap},
      {"packing_fraction", f.packing_fraction},
      {"compressibility_factor", nullptr},
      {"temperature", f.config.temperature},
      {"replicas", replicas},
      {"ranks", group.size},
      {"threads", nthreads},
      {"mach", f.mach},
      {"inflow_speed", f.config.inflow_speed},
      {"sound_speed", f.sound_speed},
      {"restitution", f.config.restitution},
      {"body_diameters", f.body.length * f.scale},
      {"flow_through_time", f.flow_through_time},
      {"warmup_time", warm},
      {"warmup_flow_throughs", warm / f.flow_through_time},
      {"steady_detected", steady_all},
      {"averaging_time", p.averaging * f.flow_through_time},
      {"simulated_time", sim_time},
      {"lattice", {{"nx", geometry.nx}, {"ny", geometry.ny}}},
      {"interrupted", interrupted},
      {"partial", interrupted},  // averaged over less than the requested time
      {"flow", describe(f)},
      {"per_replica", per_replica},
  };
  r.summary = j;
  if (root && !o.out_dir.empty()) {
    scene::write_vti(r.fields, o.out_dir + "/fields.vti");
    scene::write_json_atomic(o.out_dir + "/summary.json", r.summary);
  }
  return r;
}

}  // namespace granular
