#pragma once
// Helpers shared by the engine tests.
#include <vector>

#include "granular/engine.hpp"
#include "granular/hard_disk.hpp"

namespace granular::test {

// A large periodic box (no walls) for few-disk collision tests.
EngineConfig open_space(double size = 40.0);
// A closed square box [0, size]^2 with four walls (counter-clockwise).
EngineConfig walled_box(double size, double e_wall);

struct State {
  Vec2 r, v;
};
std::vector<State> snapshot(const Engine& e);
double kinetic_energy(const Engine& e);
Vec2 momentum(const Engine& e);

// Elastic hard disks in a periodic square box at packing fraction nu,
// melted from the lattice by `melt` collisions per particle.
Engine melted_box(int n, double nu, double melt, std::uint64_t seed, double restitution = 1.0,
                  double tc = 0.0);

// Henderson's contact value of the pair correlation (Enskog collision rate).
inline double henderson_chi(double nu) { return (1.0 - 7.0 * nu / 16.0) / ((1.0 - nu) * (1.0 - nu)); }

}  // namespace granular::test
