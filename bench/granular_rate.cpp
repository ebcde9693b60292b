// Benchmark (not a test): collisions per second of elastic hard disks at
// packing fraction 0.40 in a periodic box, for several N, and the memory
// the engine holds per particle.
//
//   granular_rate [--nu 0.4] [--per-particle 20] [--repeats 3] [--cell 0]
//                 [--look-ahead auto|records|full] [--interleave]
//                 N[:PER_PARTICLE] [N[:PER_PARTICLE] ...]
//
// Each run melts a lattice start with 5 collisions per disk (not timed),
// then times PER_PARTICLE collisions per disk. One line per N: the median
// rate over the repeats, by CPU time and by wall time. With --interleave the
// repeats are rounds over all sizes back to back (a noisy shared host then
// affects the sizes alike), and the last line gives the rate of the last N
// over the first: the ratio of the medians and the median of the per-round
// ratios, with their quartiles. Each round also times a dependent random
// read over 64 MiB (a probe of how much of the shared host's L3 this
// process gets, which moves the large-N rate from hour to hour: ~85 ns when
// much of it is ours, ~125 ns when the neighbours have it) and prints one
// line per round on stderr: probe, rates, ratio. --look-ahead sets the
// engine's prefetching (EngineConfig::look_ahead; default auto: the full
// look-ahead from ~32 MB of particle arrays up).
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "granular/box_setup.hpp"
#include "granular/engine.hpp"
#include "scene/units.hpp"

namespace {

constexpr double kMeltPerParticle = 5.0;
constexpr granular::LookAhead kAuto = granular::LookAhead::automatic;
constexpr granular::LookAhead kRecords = granular::LookAhead::records;
constexpr granular::LookAhead kFull = granular::LookAhead::full;

struct Size {
  long n = 0;
  double per_particle = 0.0;
};

struct Run {
  double cpu_rate = 0, wall_rate = 0, bytes = 0;
  std::uint64_t collisions = 0;
};

// CPU time of this process: on a shared machine it is closer to what the
// code costs than wall time (reported too).
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Dependent random reads over a 64 MiB ring of cache lines (one cycle,
// Sattolo's shuffle): nanoseconds per read, i.e. the latency a large
// system's cache misses see on this host right now (part L3, part DRAM).
class LatencyProbe {
 public:
  LatencyProbe() {
    mem_ = static_cast<std::uint64_t*>(std::aligned_alloc(std::size_t{2} << 20, kBytes));
    if (!mem_) return;
    madvise(mem_, kBytes, MADV_HUGEPAGE);  // as the engine's arrays
    std::vector<std::uint32_t> order(kLines);
    std::iota(order.begin(), order.end(), 0u);
    std::mt19937_64 rng(7);
    for (std::size_t k = kLines - 1; k > 0; --k) std::swap(order[k], order[rng() % k]);
    for (std::size_t k = 0; k < kLines; ++k) mem_[static_cast<std::size_t>(order[k]) * kStride] =
        static_cast<std::uint64_t>(order[(k + 1) % kLines]) * kStride;
  }
  ~LatencyProbe() { std::free(mem_); }
  LatencyProbe(const LatencyProbe&) = delete;
  LatencyProbe& operator=(const LatencyProbe&) = delete;
  double ns() const {
    if (!mem_) return 0.0;
    std::uint64_t at = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < kReads; ++k) at = mem_[at];
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    asm volatile("" : : "r"(at));  // the chain must be walked, its end is not used
    return ns / static_cast<double>(kReads);
  }

 private:
  static constexpr std::size_t kBytes = std::size_t{64} << 20;
  static constexpr std::size_t kLine = 64;
  static constexpr std::size_t kLines = kBytes / kLine;
  static constexpr std::size_t kStride = kLine / sizeof(std::uint64_t);
  static constexpr std::size_t kReads = 2000000;
  std::uint64_t* mem_ = nullptr;
};

long peak_rss_kb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  long kb = -1;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %ld kB", &kb) == 1) break;
  std::fclose(f);
  return kb;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

Run run_once(const Size& size, double nu, double min_cell, granular::LookAhead look_ahead,
             std::uint64_t seed) {
  granular::BoxSetup b;
  b.particles = size.n;
  b.width = b.height = std::sqrt(static_cast<double>(size.n) * scene::kDiskArea / nu);
  b.packing_fraction = nu;
  b.seed = seed;
  b.min_cell = min_cell;
  b.look_ahead = look_ahead;
  granular::Engine e = granular::make_box_engine(b);
  e.run_collisions(static_cast<std::uint64_t>(kMeltPerParticle * static_cast<double>(size.n)));
  const auto count = static_cast<std::uint64_t>(size.per_particle * static_cast<double>(size.n));
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  e.run_collisions(count);
  const double cpu = cpu_seconds() - c0;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {static_cast<double>(count) / cpu, static_cast<double>(count) / wall, e.bytes_per_particle(), count};
}

bool parse_ahead(const std::string& v, granular::LookAhead& out) {
  using granular::LookAhead;
  const LookAhead* found = v == "auto"      ? &kAuto
                           : v == "records" ? &kRecords
                           : v == "full"    ? &kFull
                                            : nullptr;
  if (!found) {
    std::fprintf(stderr, "granular_rate: --look-ahead takes auto, records or full, not '%s'\n",
                 v.c_str());
    return false;
  }
  out = *found;
  return true;
}

int usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: granular_rate [--nu 0.4] [--per-particle 20] [--repeats 3] [--cell 0]\n"
               "                     [--look-ahead auto|records|full] [--interleave]\n"
               "                     N[:PER_PARTICLE] ...\n"
               "Collisions per second (CPU and wall) of elastic disks in a periodic box.\n");
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  double nu = 0.4, per_particle = 20.0, min_cell = 0.0;
  int repeats = 3;
  bool interleave = false;
  granular::LookAhead look_ahead = kAuto;
  bool ahead_ok = true;
  std::vector<std::string> specs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--help" || a == "-h") return usage(0);
    if (a == "--nu" && has_value) nu = std::atof(argv[++i]);
    else if (a == "--per-particle" && has_value) per_particle = std::atof(argv[++i]);
    else if (a == "--repeats" && has_value) repeats = std::atoi(argv[++i]);
    else if (a == "--cell" && has_value) min_cell = std::atof(argv[++i]);
    else if (a == "--look-ahead" && has_value)
      ahead_ok = parse_ahead(argv[++i], look_ahead);
    else if (a == "--interleave") interleave = true;
    else if (!a.empty() && a[0] != '-') specs.push_back(a);
    else {
      std::fprintf(stderr, "granular_rate: unknown or incomplete option '%s'\n", a.c_str());
      return usage(2);
    }
  }
  if (!ahead_ok) return 2;
  if (specs.empty()) specs = {"10000", "32000", "1000000"};
  std::vector<Size> sizes;
  for (const std::string& spec : specs) {
    const auto colon = spec.find(':');
    Size s{std::atol(spec.substr(0, colon).c_str()),
           colon == std::string::npos ? per_particle : std::atof(spec.substr(colon + 1).c_str())};
    if (s.n < 16 || !(s.per_particle > 0.0)) {
      std::fprintf(stderr, "granular_rate: bad size '%s' (N >= 16, PER_PARTICLE > 0)\n", spec.c_str());
      return 2;
    }
    sizes.push_back(s);
  }
  if (repeats < 1 || !(nu > 0.0 && nu < 0.8)) {
    std::fprintf(stderr, "granular_rate: need --repeats >= 1 and 0 < --nu < 0.8\n");
    return 2;
  }

  std::printf("%10s %6s %12s %14s %14s %9s %12s\n", "N", "nu", "collisions", "coll/s(wall)",
              "coll/s(cpu)", "bytes/N", "peak_rss_MB");
  std::vector<std::vector<Run>> runs(sizes.size());
  const auto report = [&](std::size_t k) {
    std::vector<double> cpu, wall;
    for (const Run& r : runs[k]) cpu.push_back(r.cpu_rate), wall.push_back(r.wall_rate);
    std::printf("%10ld %6.3f %12llu %14.0f %14.0f %9.1f %12.1f\n", sizes[k].n, nu,
                static_cast<unsigned long long>(runs[k].back().collisions), quantile(wall, 0.5),
                quantile(cpu, 0.5), runs[k].back().bytes, static_cast<double>(peak_rss_kb()) / 1024.0);
    std::fflush(stdout);
  };
  std::vector<double> probe;
  if (interleave) {
    for (int r = 0; r < repeats; ++r) {
      probe.push_back(LatencyProbe().ns());  // freed before the runs: not in their peak RSS
      std::fprintf(stderr, "round %d/%d: probe %.0f ns, coll/s(cpu)", r + 1, repeats, probe.back());
      for (std::size_t k = 0; k < sizes.size(); ++k) {
        runs[k].push_back(
            run_once(sizes[k], nu, min_cell, look_ahead, static_cast<std::uint64_t>(r + 1)));
        std::fprintf(stderr, " %.0f", runs[k].back().cpu_rate);
      }
      std::fprintf(stderr, ", last/first %.3f\n", runs.back().back().cpu_rate / runs.front().back().cpu_rate);
    }
    for (std::size_t k = 0; k < sizes.size(); ++k) report(k);
  } else {
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      for (int r = 0; r < repeats; ++r)
        runs[k].push_back(
            run_once(sizes[k], nu, min_cell, look_ahead, static_cast<std::uint64_t>(r + 1)));
      report(k);
    }
  }
  if (interleave && sizes.size() >= 2) {
    std::vector<double> first, last, ratio;
    for (int r = 0; r < repeats; ++r) {
      first.push_back(runs.front()[static_cast<std::size_t>(r)].cpu_rate);
      last.push_back(runs.back()[static_cast<std::size_t>(r)].cpu_rate);
      ratio.push_back(last.back() / first.back());
    }
    std::printf("rate(N=%ld) / rate(N=%ld), CPU time: ratio of medians %.3f; per round median %.3f "
                "(quartiles %.3f-%.3f, %d rounds)\n",
                sizes.back().n, sizes.front().n, quantile(last, 0.5) / quantile(first, 0.5),
                quantile(ratio, 0.5), quantile(ratio, 0.25), quantile(ratio, 0.75), repeats);
    std::printf("host probe, dependent random read over 64 MiB: median %.0f ns (quartiles %.0f-%.0f)\n",
                quantile(probe, 0.5), quantile(probe, 0.25), quantile(probe, 0.75));
  }
  return 0;
}
