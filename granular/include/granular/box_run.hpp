#pragma once
// Validation box scenes (contract: `box:` scenes): set up, run, summarise.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace granular {

struct RunOptions {
  std::string out_dir;
  int np = 1;              // ignored by box scenes (the engine is single-threaded)
  std::string restart;     // continue from this checkpoint (OUT/checkpoint.bin of an earlier run)
  // Stop like Ctrl-C once this many collisions are done (0: never); a
  // checkpoint is written when the scene sets checkpoint_interval.
  std::uint64_t stop_after_collisions = 0;
};

// Runs the box scene `s` (s.box set), writes o.out_dir/summary.json
// atomically and returns the summary. Ctrl-C (scene::interrupted()) stops
// cleanly and still writes the summary. InputError on bad parameters.
// With granular.checkpoint_interval, OUT/checkpoint.bin is written (atomically)
// every that many collisions and when the run stops; a run restarted from it
// (RunOptions::restart, same scene) continues bit-identically.
nlohmann::json run_box_scene(const scene::Scene& s, const RunOptions& o);

}  // namespace granular
