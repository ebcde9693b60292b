#pragma once
// A body scene end to end: replicas of the supersonic granular stream past
// the body (threads, and MPI ranks when the executable provides a group),
// averaged into one lattice of fields with per-cell standard errors.
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "granular/run_options.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"

namespace granular {

struct FlowResult {
  scene::Lattice fields;
  nlohmann::json summary;
};

// How replicas are shared between processes. The default is one process.
// `sum` adds a vector element-wise over all members (in place, every member
// gets the total); `any` is a logical or over members. The library never
// links MPI: the executable fills these with MPI_Allreduce.
struct ReplicaGroup {
  int rank = 0;
  int size = 1;
  std::function<void(std::vector<double>&)> sum;
  std::function<bool(bool)> any;
};

// Runs granular.replicas replicas (seeds seed, seed+1, ...), o.np at a time
// in threads on each member of `group`; replica i runs on rank i % size.
// Rank 0 writes o.out_dir/fields.vti and summary.json atomically (plus
// particle snapshots when granular.snapshots); every rank returns the result.
// On Ctrl-C the fields averaged so far are written and summary.interrupted
// is true. InputError for scenes it cannot model, RunError for failed runs.
FlowResult run_flow_scene(const scene::Scene& s, const RunOptions& o, const ReplicaGroup& group = {});

}  // namespace granular
