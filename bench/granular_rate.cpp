// Benchmark (not a test): collisions per second of elastic hard disks at
// packing fraction 0.40 in a periodic box, for several N, and the memory
// the engine holds per particle. Usage:
//   granular_rate [--nu 0.4] [--per-particle 20] [--repeats 3] [--cell 0] N [N ...]
// Prints one line per N: median rate over the repeats (after a melt of
// 5 collisions per particle that is not timed).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <ctime>
#include <string>
#include <vector>

#include "granular/box_setup.hpp"
#include "granular/engine.hpp"

namespace {

constexpr double kMeltPerParticle = 5.0;

// CPU time of this process: on a shared machine it is closer to what the
// code costs than wall time (reported too).
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

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

}  // namespace

int main(int argc, char** argv) {
  double nu = 0.4, per_particle = 20.0, min_cell = 0.0;
  int repeats = 3;
  std::vector<long> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--nu" && i + 1 < argc) nu = std::atof(argv[++i]);
    else if (a == "--per-particle" && i + 1 < argc) per_particle = std::atof(argv[++i]);
    else if (a == "--repeats" && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (a == "--cell" && i + 1 < argc) min_cell = std::atof(argv[++i]);
    else sizes.push_back(std::atol(a.c_str()));
  }
  if (sizes.empty()) sizes = {10000, 32000, 1000000};
  std::printf("%10s %6s %12s %9s %9s %14s %14s %9s %12s\n", "N", "nu", "collisions", "wall_s", "cpu_s",
              "coll/s(wall)", "coll/s(cpu)", "bytes/N", "peak_rss_MB");
  for (const long n : sizes) {
    std::vector<double> rates, cpu_rates;
    double bytes = 0, secs = 0, cpu = 0;
    std::uint64_t done = 0;
    for (int r = 0; r < repeats; ++r) {
      granular::BoxSetup b;
      b.particles = n;
      b.width = b.height = std::sqrt(static_cast<double>(n) * std::numbers::pi / 4.0 / nu);
      b.packing_fraction = nu;
      b.seed = static_cast<std::uint64_t>(r + 1);
      b.min_cell = min_cell;
      granular::Engine e = granular::make_box_engine(b);
      e.run_collisions(static_cast<std::uint64_t>(kMeltPerParticle * static_cast<double>(n)));
      const auto count = static_cast<std::uint64_t>(per_particle * static_cast<double>(n));
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpu_seconds();
      e.run_collisions(count);
      cpu = cpu_seconds() - c0;
      secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rates.push_back(static_cast<double>(count) / secs);
      cpu_rates.push_back(static_cast<double>(count) / cpu);
      bytes = e.bytes_per_particle();
      done = count;
    }
    std::sort(rates.begin(), rates.end());
    std::sort(cpu_rates.begin(), cpu_rates.end());
    std::printf("%10ld %6.3f %12llu %9.3f %9.3f %14.0f %14.0f %9.1f %12.1f\n", n, nu,
                static_cast<unsigned long long>(done), secs, cpu, rates[rates.size() / 2],
                cpu_rates[cpu_rates.size() / 2], bytes, static_cast<double>(peak_rss_kb()) / 1024.0);
    std::fflush(stdout);
  }
  return 0;
}
