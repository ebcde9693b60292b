// Benchmark (not a test): collisions per CPU second of the event-driven
// engine in the dilute supersonic stream past a body, the flow stage's
// workload (docs/bench_granular_flow.md).
//
//   granular_stream_rate [--scene FILE] [--flow-throughs 3] [--rounds 3]
//                        [--seed 1] [CELL ...]
//
// Each run sets up the scene's flow exactly as `granular run` does (the
// default scene is the wedge M3/10 at its default particle count), builds
// the FlowSimulation (prefill included) and runs it for the given number of
// flow-through times, no field sampling. The rate is disk-disk collisions
// per CPU second of that whole run: inflow injection, removal at the
// outflow, wall and vertex hits and cell crossings all count in the time,
// only disk-disk collisions in the numerator.
//
// CELL sets the engine's cell side in diameters (FlowConfig::cell): "auto"
// (the default, matched to the inflow) or a number; prefixed with "fixed:"
// the cells do not drift with the stream (FlowConfig::comoving_cells =
// false): "fixed:1" is the engine as it was before 2026-12-02. Several settings are run in
// interleaved rounds (each round runs every setting once, with that round's seed), so that a noisy
// shared host affects them alike; the last line gives the rate of the last
// setting over the first: the ratio of the medians and the median of the
// per-round ratios. One line per run goes to stderr.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "granular/engine.hpp"
#include "granular/flow_setup.hpp"
#include "scene/scene.hpp"

namespace {

struct Setting {
  std::string label;
  double cell = 0.0;  // 0: automatic
  bool comoving = true;
};

struct Run {
  double cpu = 0.0, rate = 0.0;
  granular::Stats stats;
  granular::EventCounts counts;
  double cell_x = 0.0, cell_y = 0.0;
};

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool parse_setting(const std::string& a, Setting& out) {
  out.label = a;
  std::string v = a;
  const std::string fixed = "fixed:";
  if (v.rfind(fixed, 0) == 0) {
    out.comoving = false;
    v = v.substr(fixed.size());
  }
  if (v == "auto") return true;
  char* end = nullptr;
  out.cell = std::strtod(v.c_str(), &end);
  return *end == '\0' && out.cell >= 1.0;
}

Run run_once(const granular::FlowSetup& setup, const Setting& s, double flow_throughs,
             std::uint64_t seed) {
  granular::FlowConfig cfg = setup.config;
  cfg.seed = seed;
  cfg.cell = s.cell;
  cfg.comoving_cells = s.comoving;
  const double c0 = cpu_seconds();
  granular::FlowSimulation sim(cfg);
  sim.run_until(flow_throughs * setup.flow_through_time);
  Run r;
  r.cpu = cpu_seconds() - c0;
  r.stats = sim.engine().stats();
  r.counts = sim.engine().event_counts();
  r.rate = static_cast<double>(r.stats.disk_collisions) / r.cpu;
  r.cell_x = sim.engine().cell_size().x;
  r.cell_y = sim.engine().cell_size().y;
  return r;
}

int usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: granular_stream_rate [--scene FILE] [--flow-throughs 3] [--rounds 3]\n"
               "                            [--seed 1] [CELL ...]   (CELL: [fixed:]auto or "
               "[fixed:]diameters)\n"
               "Disk-disk collisions per CPU second of the flow stage's stream past a body.\n");
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = SOURCE_DIR "/pipeline/cases/wedge_M3_10.yaml";
  double flow_throughs = 3.0;
  int rounds = 3;
  std::uint64_t seed = 1;
  std::vector<Setting> settings;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    Setting s;
    if (a == "--help" || a == "-h") return usage(0);
    if (a == "--scene" && has_value)
      scene_path = argv[++i];
    else if (a == "--flow-throughs" && has_value)
      flow_throughs = std::atof(argv[++i]);
    else if (a == "--rounds" && has_value)
      rounds = std::atoi(argv[++i]);
    else if (a == "--seed" && has_value)
      seed = std::strtoull(argv[++i], nullptr, 10);
    else if (!a.empty() && a[0] != '-' && parse_setting(a, s))
      settings.push_back(s);
    else {
      std::fprintf(stderr, "granular_stream_rate: unknown or bad argument '%s'\n", a.c_str());
      return usage(2);
    }
  }
  if (rounds < 1 || !(flow_throughs > 0.0)) {
    std::fprintf(stderr, "granular_stream_rate: need --rounds >= 1 and --flow-throughs > 0\n");
    return 2;
  }
  if (settings.empty()) settings.push_back(Setting{"auto"});
  const granular::FlowSetup setup = granular::make_flow_setup(scene::load_scene(scene_path));
  std::printf(
      "scene %s: %.0f disks expected, U = %.3f, %.2f flow-through times of %.2f, %d rounds\n",
      scene_path.c_str(), setup.expected_particles, setup.config.inflow_speed, flow_throughs,
      setup.flow_through_time, rounds);

  std::vector<std::vector<Run>> runs(settings.size());
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t k = 0; k < settings.size(); ++k) {
      runs[k].push_back(
          run_once(setup, settings[k], flow_throughs, seed + static_cast<std::uint64_t>(r)));
      const Run& x = runs[k].back();
      std::fprintf(stderr,
                   "round %d cell %s: %.0f disk collisions/s (cpu %.2f s), %zu disks at the end, "
                   "recoveries %llu, "
                   "max overlap %.1e\n",
                   r + 1, settings[k].label.c_str(), x.rate, x.cpu, x.stats.particles,
                   static_cast<unsigned long long>(x.stats.recoveries), x.stats.max_overlap);
    }
  }
  std::printf("%10s %11s %14s %12s %10s %10s %10s %10s %10s %10s\n", "cell", "cell_dxdy",
              "coll/s(cpu)", "disk_coll", "events/c", "cross/c", "recheck/c", "stale/c", "wall/c",
              "insert/c");
  for (std::size_t k = 0; k < settings.size(); ++k) {
    std::vector<double> rates;
    for (const Run& x : runs[k]) rates.push_back(x.rate);
    const Run& x = runs[k].back();
    const double c = static_cast<double>(x.stats.disk_collisions);
    char dims[32];
    std::snprintf(dims, sizeof dims, "%.2fx%.2f", x.cell_x, x.cell_y);
    std::printf("%10s %11s %14.0f %12llu %10.2f %10.2f %10.3f %10.3f %10.4f %10.4f\n",
                settings[k].label.c_str(), dims, median(rates),
                static_cast<unsigned long long>(x.stats.disk_collisions),
                static_cast<double>(x.counts.events) / c,
                static_cast<double>(x.counts.cell_crossings) / c,
                static_cast<double>(x.counts.wall_rechecks) / c,
                static_cast<double>(x.counts.repredictions) / c,
                static_cast<double>(x.stats.wall_collisions) / c,
                static_cast<double>(x.stats.inserted) / c);
  }
  if (settings.size() >= 2) {
    std::vector<double> first, last, ratio;
    for (int r = 0; r < rounds; ++r) {
      first.push_back(runs.front()[static_cast<std::size_t>(r)].rate);
      last.push_back(runs.back()[static_cast<std::size_t>(r)].rate);
      ratio.push_back(last.back() / first.back());
    }
    std::printf(
        "rate(%s) / rate(%s), CPU time: ratio of medians %.3f; per round median %.3f (%d rounds)\n",
        settings.back().label.c_str(), settings.front().label.c_str(), median(last) / median(first),
        median(ratio), rounds);
  }
  return 0;
}
