#pragma once
// Validation box scenes (contract: `box:` scenes): set up, run, summarise.
#include <string>

#include <nlohmann/json.hpp>

#include "granular/run_options.hpp"
#include "scene/scene.hpp"

namespace granular {

// Runs the box scene `s` (s.box set), writes o.out_dir/summary.json
// atomically and returns the summary. Ctrl-C (scene::interrupted()) stops
// cleanly and still writes the summary. InputError on bad parameters.
// With granular.checkpoint_interval, OUT/checkpoint.bin is written (atomically)
// every that many collisions and when the run stops; a run restarted from it
// (RunOptions::restart, same scene) continues bit-identically.
nlohmann::json run_box_scene(const scene::Scene& s, const RunOptions& o);

}  // namespace granular
