#pragma once
// Validation box scenes (contract: `box:` scenes): set up, run, summarise.
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace granular {

struct RunOptions {
  std::string out_dir;
  int np = 1;
};

// Runs the box scene `s` (s.box set), writes o.out_dir/summary.json
// atomically and returns the summary. Ctrl-C (scene::interrupted()) stops
// cleanly and still writes the summary. InputError on bad parameters.
nlohmann::json run_box_scene(const scene::Scene& s, const RunOptions& o);

}  // namespace granular
