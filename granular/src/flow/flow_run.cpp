#include "granular/flow_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "granular/flow_fields.hpp"
#include "granular/flow_replica.hpp"
#include "granular/flow_setup.hpp"
#include "granular/precision_stop.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/group_fields.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"

namespace granular {

namespace {

// The shock's interval comes from the spread between averaging groups
// (shockfit/group_interval.hpp): each replica's averaging is dealt, slice by
// slice, into groups, about this many in all (Student's t with groups - 1
// degrees of freedom). Slices of a quarter flow-through time: short enough
// that every group samples the whole averaging (a slow drift of the shock
// while it settles is then common to all groups, not spread between them),
// long enough that the shock position hardly correlates from one slice to
// the next (docs/shockfit.md, "Interval coverage": half-widths 0.1-1.1x
// too wide at 0.5, 0.6x too narrow at 0.0625).
constexpr int kIntervalGroups = 8;
constexpr double kGroupSliceFlowThroughs = 0.25;
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
  for (const FieldSums& g : r.groups) v.insert(v.end(), g.raw().begin(), g.raw().end());
  return v;
}

// Where each replica's numbers sit in the vector summed over ranks: kSlots
// scalars, then `groups` blocks of field sums.
struct Layout {
  int replicas = 1;
  int groups = 1;  // averaging groups per replica
  std::size_t ncell = 0, block_size = 0, stride = 0;
};

Layout layout_for(const scene::GranularParams& p, const scene::Lattice& geometry) {
  Layout l;
  l.replicas = p.replicas;
  l.ncell = static_cast<std::size_t>(geometry.nx) * static_cast<std::size_t>(geometry.ny);
  l.block_size = FieldSums(l.ncell).raw().size();
  l.groups = std::max(1, (kIntervalGroups + l.replicas - 1) / l.replicas);
  l.stride = kSlots + static_cast<std::size_t>(l.groups) * l.block_size;
  return l;
}

// The replicas this member of the group runs: replica i on rank i % size.
std::vector<int> replicas_of(const ReplicaGroup& group, int replicas) {
  std::vector<int> mine;
  for (int i = 0; i < replicas; ++i)
    if (i % std::max(1, group.size) == group.rank) mine.push_back(i);
  return mine;
}

// This member's replicas, each keeping its simulation between chunks, run
// o.np at a time in threads; the calling thread shows progress (rank 0). A
// failure anywhere is rethrown on every rank.
class ReplicaPool {
 public:
  ReplicaPool(const scene::Scene& s, const FlowSetup& f, const scene::Lattice& geometry,
              const RunOptions& o, const ReplicaGroup& group, const Layout& l,
              double planned_flow_throughs)
      : group_(group),
        l_(l),
        mine_(replicas_of(group, l.replicas)),
        nthreads_(std::max(1, std::min(o.np, static_cast<int>(mine_.size())))),
        bar_("granular " + s.name,
             (s.granular.warmup.value_or(kWarmupGuessFlowThroughs) + planned_flow_throughs) *
                 f.flow_through_time * static_cast<double>(mine_.size()),
             "t") {
    const scene::GranularParams& p = s.granular;
    for (const int i : mine_) {
      ReplicaPlan plan;
      plan.seed = p.seed + static_cast<std::uint64_t>(i);
      plan.groups = l.groups;
      plan.group_slice_flow_throughs = kGroupSliceFlowThroughs;
      plan.warmup = p.warmup;
      if (p.snapshots && !o.out_dir.empty())
        plan.snapshot_path = o.out_dir + "/snapshots/replica_" + std::to_string(i) + ".csv";
      replicas_.push_back(std::make_unique<FlowReplica>(f, geometry, plan));
    }
  }

  int threads() const { return nthreads_; }

  // `snapshots` more on every replica (0: the warm-up alone).
  void average(long snapshots) {
    run([&](FlowReplica& r) { r.average(snapshots, &progress_); });
  }

  // Every replica's outcome so far, in its stride of the vector summed over
  // the group.
  std::vector<double> gather() const {
    std::vector<double> all(l_.stride * static_cast<std::size_t>(l_.replicas), 0.0);
    for (std::size_t k = 0; k < mine_.size(); ++k) {
      std::vector<double> v = pack(replicas_[k]->outcome());
      v.resize(l_.stride, 0.0);  // no groups yet before the averaging
      std::copy(v.begin(), v.end(),
                all.begin() +
                    static_cast<std::ptrdiff_t>(l_.stride * static_cast<std::size_t>(mine_[k])));
    }
    if (group_.sum && group_.size > 1) group_.sum(all);
    return all;
  }

  void finish() {
    run([](FlowReplica& r) { r.write_snapshot(); });
    if (group_.rank == 0) bar_.finish();
  }

 private:
  const ReplicaGroup& group_;
  Layout l_;
  std::vector<int> mine_;
  int nthreads_;
  scene::Progress bar_;
  std::atomic<double> progress_{0.0};
  std::vector<std::unique_ptr<FlowReplica>> replicas_;

  template <class Task>
  void run(const Task& task) {
    std::atomic<std::size_t> next{0};
    std::mutex failure_mutex;
    std::exception_ptr failure;
    std::atomic<int> running{nthreads_};
    auto worker = [&]() {
      for (std::size_t k = next++; k < replicas_.size(); k = next++) {
        try {
          task(*replicas_[k]);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failure_mutex);
          if (!failure) failure = std::current_exception();
        }
      }
      --running;
    };
    std::vector<std::thread> threads;
    for (int t = 0; t < nthreads_; ++t) threads.emplace_back(worker);
    if (group_.rank == 0)
      while (running.load() > 0) {
        bar_.update(progress_.load());
        std::this_thread::sleep_for(kProgressPoll);
      }
    for (auto& t : threads) t.join();
    const bool failed_here = static_cast<bool>(failure);
    const bool failed_any = group_.any ? group_.any(failed_here) : failed_here;
    if (failure) std::rethrow_exception(failure);
    if (failed_any) throw scene::RunError("a replica failed on another rank");
  }
};

// The replicas' outcomes combined: counters summed, energies and particle
// counts averaged, field blocks that hold snapshots kept for averaging.
struct Combined {
  std::vector<FieldSums> blocks;  // the averaging groups that hold snapshots
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
    for (int g = 0; g < l.groups; ++g) {
      FieldSums fs(l.ncell);
      const double* src = v + kSlots + static_cast<std::size_t>(g) * l.block_size;
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
      {"simulated_time", c.sim_time},
      {"lattice", {{"nx", geometry.nx}, {"ny", geometry.ny}}},
      {"interrupted", c.interrupted},
      {"partial", c.interrupted},  // averaged over less than the requested time
      {"flow", describe(f)},
      {"per_replica", c.per_replica},
  };
}

}  // namespace

namespace {

// Where the averaging stopped, and what the precision checks saw.
struct AveragingOutcome {
  long snapshots = 0;
  std::string stopped_by;
  nlohmann::json checks = nlohmann::json::array();
  PrecisionMeasure last;
  std::vector<PrecisionCheck> history;
};

FlowResult fields_so_far(const ReplicaPool& pool, const FlowSetup& f,
                         const scene::Lattice& geometry, const Layout& l, std::uint64_t seed,
                         Combined& c) {
  c = combine(pool.gather(), l, seed);
  FlowResult r;
  if (!c.blocks.empty()) {
    r.fields = make_fields(f, geometry, c.blocks);
    r.groups = make_group_fields(r.fields, c.blocks);
  }
  return r;
}

bool anyone(const ReplicaGroup& group, bool here) {
  return group.any ? group.any(here) : here;
}

// The target counts as met when two consecutive checks meet it with the
// same kind of shock. The interval is itself an estimate and moves by
// +-10-20% from chunk to chunk (wedge M4.5/12, docs/granular_flow.md): one
// check alone stops on the first lucky dip, and a noisy early fit that
// classifies an attached shock as a bow shock would be judged by the wrong
// quantity.
// And the shock must have stopped moving: an interval from the spread of
// averaging groups describes another run's scatter, not a drift common to
// all groups while the flow still settles (wedge M3/10: 23.8, 25.3, 26.2,
// 26.4 deg at 1, 1.5, 2, 2.5 flow-through times, docs/granular_flow.md).
bool met(const PrecisionGoal& goal, const PrecisionMeasure& previous, const PrecisionMeasure& now) {
  if (!(now.half_width <= goal.target && previous.half_width <= goal.target &&
        previous.quantity == now.quantity))
    return false;
  const double moved = std::abs(now.value - previous.value) * now.value_to_position;
  return !std::isfinite(moved) || moved <= goal.target;
}

// Chunks of averaging until the goal is met, the budget would be overrun or
// the planned time is averaged. Without a goal or a budget: one chunk.
AveragingOutcome average(ReplicaPool& pool, const scene::GranularParams& p, const FlowSetup& f,
                         const scene::Lattice& geometry, const Layout& l, const ReplicaGroup& group,
                         const PrecisionGoal& goal, const scene::CpuStopwatch& cpu) {
  const double tau = f.flow_through_time;
  const double dt = snapshot_interval(f, geometry);
  auto snapshots_for = [&](double flow_throughs) {
    return std::max<long>(1, std::lround(flow_throughs * tau / dt));
  };
  const long cap = snapshots_for(goal.active() ? p.max_averaging : p.averaging);
  const bool chunked = goal.active() || p.cpu_budget.has_value();
  // Chunks end at whole snapshots nearest to 1, 1.5, 2, ... flow-through
  // times (counted from the start, so rounding does not accumulate), the
  // last at the cap.
  const double first_check =
      std::max(kFirstCheckFlowThroughs, goal.min_flow_throughs - kCheckEveryFlowThroughs);
  double boundary = chunked ? (goal.active() ? first_check : kCheckEveryFlowThroughs)
                            : std::numeric_limits<double>::infinity();
  // The last snapshot of the chunk after `done` that ends at the check `at`.
  auto chunk_end = [&](double at, long done) {
    return std::clamp(std::isfinite(at) ? snapshots_for(at) : cap, done + 1, cap);
  };
  long chunk = chunk_end(boundary, 0);

  AveragingOutcome out;
  int unpaid = 0;   // checks in a row at which the next chunk would not pay
  pool.average(0);  // the warm-up, so that the first chunk's cost is the averaging's
  double mark = cpu.seconds();
  // CPU seconds of `snapshots` more at the rate of the chunk just averaged,
  // its check included (`now`: the CPU clock read after the check).
  auto at_chunk_rate = [&](double now, long snapshots) {
    return (now - mark) * static_cast<double>(snapshots) / static_cast<double>(chunk);
  };
  while (true) {
    pool.average(chunk);
    out.snapshots += chunk;
    if (anyone(group, scene::interrupted())) {
      out.stopped_by = "interrupted";
      break;
    }
    if (goal.active()) {
      Combined c;
      const FlowResult r = fields_so_far(pool, f, geometry, l, p.seed, c);
      const PrecisionMeasure previous = out.last;
      out.last = goal.measure(r.fields, r.groups);
      const double averaged = static_cast<double>(out.snapshots) * dt / tau;  // flow-through times
      out.checks.push_back(
          {{"flow_throughs", averaged},
           {"half_width", std::isfinite(out.last.half_width) ? nlohmann::json(out.last.half_width)
                                                             : nlohmann::json(nullptr)},
           {"quantity", out.last.quantity},
           {"value", std::isfinite(out.last.value) ? nlohmann::json(out.last.value)
                                                   : nlohmann::json(nullptr)},
           {"cpu_seconds", cpu.seconds()},
           {"details", out.last.details}});
      out.history.push_back({averaged, out.last.half_width, out.last.quantity});
      // The nominal check time, not the snapshot-rounded one: a check meant
      // for the minimum counts there.
      const bool may_stop = boundary >= goal.min_flow_throughs;
      if (anyone(group, may_stop && met(goal, previous, out.last))) {
        out.stopped_by = "precision";
        break;
      }
      if (anyone(group, may_stop && interval_plateaued(out.history))) {
        out.stopped_by = "plateau";
        break;
      }
      if (goal.downstream_cpu && out.snapshots < cap) {
        const long next =
            chunk_end(boundary + kCheckEveryFlowThroughs, out.snapshots) - out.snapshots;
        const double next_cpu = at_chunk_rate(cpu.seconds(), next);
        const double saving =
            expected_saving(goal.downstream_cpu, out.last.value, out.last.half_width, averaged,
                            static_cast<double>(next) * dt / tau);
        unpaid = chunk_pays(saving, next_cpu) ? 0 : unpaid + 1;
        nlohmann::json& check = out.checks.back();
        check["next_chunk_cpu_seconds"] = next_cpu;
        check["expected_saving_cpu_seconds"] =
            std::isfinite(saving) ? nlohmann::json(saving) : nlohmann::json(nullptr);
        if (anyone(group, may_stop && unpaid >= kUnpaidChecksToStop)) {
          out.stopped_by = "cost";
          break;
        }
      }
    }
    if (out.snapshots >= cap) {
      out.stopped_by = "averaging";
      break;
    }
    boundary += kCheckEveryFlowThroughs;
    const long next = chunk_end(boundary, out.snapshots) - out.snapshots;
    const double now = cpu.seconds();
    const double next_cost = at_chunk_rate(now, next);
    mark = now;
    if (anyone(group, p.cpu_budget && now + next_cost > *p.cpu_budget)) {
      out.stopped_by = "budget";
      break;
    }
    chunk = next;
  }
  return out;
}

nlohmann::json precision_summary(const PrecisionGoal& goal, const AveragingOutcome& a) {
  if (!goal.active()) return nullptr;
  auto num = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  return {{"target_half_width", goal.target},
          {"target_unit", goal.unit},
          {"target_source", goal.target_source},
          {"min_flow_throughs", goal.min_flow_throughs},
          {"half_width", num(a.last.half_width)},
          {"quantity", a.last.quantity},
          {"checks", a.checks}};
}

}  // namespace

FlowResult run_flow_scene(const scene::Scene& s, const RunOptions& o, const ReplicaGroup& group,
                          const PrecisionGoal& goal) {
  const auto wall_start = std::chrono::steady_clock::now();
  const scene::CpuStopwatch cpu;
  const FlowSetup f = make_flow_setup(s);
  const scene::GranularParams& p = s.granular;
  const scene::Lattice geometry = flow_lattice(f, p.lattice_nx, p.lattice_ny);
  const Layout l = layout_for(p, geometry);
  if (!o.out_dir.empty()) scene::make_dirs(o.out_dir);
  if (p.snapshots && !o.out_dir.empty()) scene::make_dirs(o.out_dir + "/snapshots");
  if (!goal.active() && p.asks_precision() && group.rank == 0)
    scene::log_line(
        "granular: granular.target_half_width is judged by the pipeline (it needs shockfit); "
        "this run averages granular.averaging");

  ReplicaPool pool(s, f, geometry, o, group, l, goal.active() ? p.max_averaging : p.averaging);
  const AveragingOutcome a = average(pool, p, f, geometry, l, group, goal, cpu);
  pool.finish();

  Combined c;
  FlowResult r = fields_so_far(pool, f, geometry, l, p.seed, c);
  if (c.blocks.empty())
    throw scene::RunError(
        c.interrupted ? "interrupted during warm-up: no fields averaged yet, nothing written"
                      : "no snapshots were averaged");
  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.summary = flow_summary(s, f, geometry, c, wall_seconds, group.size, pool.threads());
  const double averaged = static_cast<double>(a.snapshots) * snapshot_interval(f, geometry);
  r.summary["averaging_time"] = averaged;
  r.summary["averaging_flow_throughs"] = averaged / f.flow_through_time;
  r.summary["stopped_by"] = a.stopped_by;
  r.summary["cpu_budget"] = p.cpu_budget ? nlohmann::json(*p.cpu_budget) : nlohmann::json(nullptr);
  r.summary["precision"] = precision_summary(goal, a);
  r.summary["cpu_seconds"] = cpu.seconds();
  if (group.rank == 0 && !o.out_dir.empty()) {
    scene::write_vti(r.fields, o.out_dir + "/fields.vti");
    if (!r.groups.empty())
      scene::write_vti(scene::pack_groups(r.groups), o.out_dir + "/groups.vti");
    scene::write_json_atomic(o.out_dir + "/summary.json", r.summary);
  }
  return r;
}

}  // namespace granular
