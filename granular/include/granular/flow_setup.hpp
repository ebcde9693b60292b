#pragma once
// From a body scene to the engine's flow configuration: the scale (particle
// diameters per body length), the walls, the inflow state and its granular
// Mach number. Engine units: lengths in particle diameters d, mass m = 1,
// temperature in units of the inflow temperature T (so T = 1), times in
// d / sqrt(T/m). Scene units: body lengths.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "granular/engine.hpp"
#include "granular/hard_disk.hpp"
#include "scene/body.hpp"
#include "scene/scene.hpp"

namespace granular {

// Adiabatic sound speed of the hard-disk fluid (m = 1): the internal energy
// is kinetic only (c_v = 1 per disk in 2D), so
// c^2 = T (Z + nu dZ/dnu + Z^2); the dilute limit is c^2 = 2T (gamma = 2).
double sound_speed(double nu, double temperature);
// Granular Mach number of the scene: granular.mach, else freestream.mach.
double granular_mach(const scene::Scene& s);

struct FlowSetup {
  scene::BodyGeometry body;     // scene units
  scene::Domain domain;         // scene units: the lattice spans it (scene_domain)
  // Simulated rectangle, scene units: the domain, extended upstream and
  // sideways for blunt bodies, whose granular bow shock stands off further
  // than the gas-dynamic estimate the scene domain is sized for.
  scene::Domain sim_domain;
  double scale = 1.0;           // particle diameters per scene length unit
  double mach = 3.0;            // granular Mach number U / c
  double packing_fraction = 0;  // inflow
  double number_density = 0;    // inflow, disks per d^2
  double sound_speed = 0;       // inflow, sqrt(T/m) units
  double flow_through_time = 0; // domain length / U
  double fluid_area = 0;        // domain minus body, d^2
  double expected_particles = 0;  // inflow density times fluid area
  FlowConfig config;            // engine units; seed set per replica
};

// The body's walls inside the domain, in scene units, each chain traversed
// with the body on its right (the engine's convention): the outline clipped
// to the domain rectangle, pieces along a domain face (the outflow plane,
// the symmetry plane) dropped. A body wholly inside gives one closed loop
// (first point repeated). Works for bodies whose most upstream point is off
// the symmetry line (a notch facing the stream), unlike a walk from the nose.
std::vector<std::vector<scene::Vec2>> body_chains(const scene::BodyGeometry& g, const scene::Domain& d);

// Throws InputError (naming the key) for scenes the flow cannot model.
FlowSetup make_flow_setup(const scene::Scene& s);

// Scene <-> engine coordinates (the engine frame is the scene frame scaled).
inline scene::Vec2 to_engine(const FlowSetup& f, scene::Vec2 p) { return f.scale * p; }
inline scene::Vec2 to_scene(const FlowSetup& f, scene::Vec2 p) { return p / f.scale; }

// Resolved flow parameters as JSON (for --dry-run and summary.json).
nlohmann::json describe(const FlowSetup& f);

}  // namespace granular
