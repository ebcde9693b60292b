#pragma once
// How the granular executable runs a scene: shared by box scenes
// (box_run.hpp) and body scenes (flow_run.hpp).
#include <cstdint>
#include <string>

namespace granular {

struct RunOptions {
  std::string out_dir;
  // Threads per process: body scenes run this many replicas at a time (MPI
  // ranks, when the executable provides them, multiply it); box scenes run
  // one single-threaded engine and ignore it.
  int np = 1;
  std::string restart;     // continue from this checkpoint (OUT/checkpoint.bin of an earlier run)
  // Stop like Ctrl-C once this many collisions are done (0: never); a
  // checkpoint is written when the scene sets checkpoint_interval.
  std::uint64_t stop_after_collisions = 0;
};

}  // namespace granular
