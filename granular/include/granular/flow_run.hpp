#pragma once
// A body scene end to end: replicas of the supersonic granular stream past
// the body (threads, and MPI ranks when the executable provides a group),
// averaged into one lattice of fields with per-cell standard errors.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "granular/run_options.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"

namespace granular {

struct FlowResult {
  scene::Lattice fields;
  // The fields of each averaging group alone, for the shock's interval
  // (about 8 groups of interleaved half flow-through slices over all
  // replicas; make_group_fields; empty with fewer than two groups).
  std::vector<scene::Lattice> groups;
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

// How precise the shock of fields averaged so far is. The library knows no
// shock locator (a later stage): the caller measures it.
struct PrecisionMeasure {
  // 95% half-width of the shock position, body lengths; NaN while no shock
  // is found (the averaging then goes on).
  double half_width = std::numeric_limits<double>::quiet_NaN();
  std::string quantity;  // what it was derived from, e.g. "shock_angle", "standoff"
  // The shock's value (an angle, a standoff) and the body lengths the shock
  // moves per unit of it: two checks must also agree on where the shock is
  // (NaN: not judged). An interval says how far another run would be; a
  // shock still settling as the run averages is not placed by it.
  double value = std::numeric_limits<double>::quiet_NaN();
  double value_to_position = std::numeric_limits<double>::quiet_NaN();
  nlohmann::json details = nlohmann::json::object();  // recorded with the check
};

// Precision on demand: average until measure(fields so far).half_width <=
// target. Without a measure the run averages granular.averaging.
struct PrecisionGoal {
  // In `unit`: body lengths, unless the measure says how precise the shock
  // is in another quantity (an angle in degrees); the measure's half_width
  // and value then use that unit and value_to_position is 1.
  double target = std::numeric_limits<double>::quiet_NaN();
  std::string unit = "body lengths";
  std::string target_source;  // how the target was set, for the summary
  // No stop before this many flow-through times are averaged: checks start
  // one check interval earlier, so that two can meet the target there.
  double min_flow_throughs = 0.0;
  std::function<PrecisionMeasure(const scene::Lattice& fields,
                                 const std::vector<scene::Lattice>& groups)>
      measure;
  // CPU seconds the later stages are expected to spend when the shock is
  // known to within `half_width` at `value` (both in the measure's unit);
  // NaN where that cannot be priced. Empty: averaging is not priced, and
  // only the target, the plateau, the budget and the cap stop it.
  std::function<double(double value, double half_width)> downstream_cpu;
  bool active() const { return static_cast<bool>(measure); }
};

// Runs granular.replicas replicas (seeds seed, seed+1, ...), o.np at a time
// in threads on each member of `group`; replica i runs on rank i % size.
// Rank 0 writes o.out_dir/fields.vti, groups.vti (the averaging groups'
// fields) and summary.json atomically (plus
// particle snapshots when granular.snapshots); every rank returns the result.
// On Ctrl-C the fields averaged so far are written and summary.interrupted
// is true. InputError for scenes it cannot model, RunError for failed runs.
//
// The averaging stops at the first of (summary.stopped_by): "precision"
// (goal active and met by two consecutive checks with the same quantity,
// between which the shock moved by no more than the target;
// checks every kCheckEveryFlowThroughs from kFirstCheckFlowThroughs on, none
// stopping before the goal's min_flow_throughs),
// "plateau" (the interval stopped shrinking with averaging time:
// granular/precision_stop.hpp), "cost" (the goal prices the later stages, and on two checks in a
// row the next chunk's CPU at the last chunk's rate exceeded what it was expected to save them:
// granular/precision_stop.hpp), "budget" (granular.cpu_budget: the next chunk would
// overrun it at the last chunk's rate) and "averaging" (granular.max_averaging with a goal, else
// granular.averaging). Every replica keeps its simulation between chunks and snapshot times count
// from the end of its warm-up, so a run stopped after N flow-through times has the fields of an
// uninterrupted run with averaging: N (replicas >= 2).
FlowResult run_flow_scene(const scene::Scene& s, const RunOptions& o,
                          const ReplicaGroup& group = {}, const PrecisionGoal& goal = {});

// Chunking of the averaging, in flow-through times: the first precision
// check, and the interval between checks (also the budget's granularity).
inline constexpr double kFirstCheckFlowThroughs = 1.0;
inline constexpr double kCheckEveryFlowThroughs = 0.5;

}  // namespace granular
