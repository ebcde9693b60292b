#pragma once
// CPU seconds (user + system) spent by this process's threads and by its
// finished, waited-for child processes (an OpenFOAM solver and, through
// mpirun, every rank). Costs are compared in CPU seconds because wall
// seconds move with the load of a shared machine.
#include <sys/resource.h>

namespace scene {

inline double rusage_cpu_seconds(int who) {
  rusage u{};
  getrusage(who, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Waited-for children only (a meshing child, a solver).
inline double children_cpu_seconds() { return rusage_cpu_seconds(RUSAGE_CHILDREN); }

inline double cpu_seconds_now() { return rusage_cpu_seconds(RUSAGE_SELF) + children_cpu_seconds(); }

// CPU seconds since construction; valid for work done in sequence (a child
// counts once it has been waited for).
class CpuStopwatch {
 public:
  CpuStopwatch() : start_(cpu_seconds_now()) {}
  double seconds() const { return cpu_seconds_now() - start_; }

 private:
  double start_;
};

}  // namespace scene
