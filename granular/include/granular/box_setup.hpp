#pragma once
// Box scenes resolved into engine terms (used by run_box_scene and tests).
#include <cstdint>

#include "granular/engine.hpp"
#include "scene/scene.hpp"

namespace granular {

struct BoxSetup {
  double width = 100, height = 100;  // diameters
  bool periodic = true;              // else four walls
  std::int64_t particles = 0;
  double packing_fraction = 0.0;
  double restitution = 1.0, restitution_wall = 1.0, tc = 0.0;
  Vec2 gravity{0, 0};
  std::uint64_t seed = 1;
  double min_cell = 0.0;  // EngineConfig::min_cell (0: one diameter)
  LookAhead look_ahead = LookAhead::automatic;  // EngineConfig::look_ahead
};

// Validates the scene's box and granular sections (InputError naming the
// file and key).
BoxSetup resolve_box(const scene::Scene& s);

// Disks of diameter 1 and mass 1 on a randomly occupied square lattice,
// Maxwellian velocities at exactly T = 1 with zero total momentum.
Engine make_box_engine(const BoxSetup& b);

}  // namespace granular
