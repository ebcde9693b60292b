#pragma once
// Generators of broken inputs for the fuzz suite, all driven by one seeded
// generator so that a failing case can be replayed from its number.
#include <random>
#include <string>
#include <vector>

namespace fuzz {

using Rng = std::mt19937_64;

// A hostile replacement for a number: NaN, infinities, huge, tiny,
// negative, 2^63, a string, a list, a mapping, empty.
std::string hostile_value(Rng& rng);

// One mutation of a scene text (block-style YAML); `kind` names it.
std::string mutate_scene(const std::string& text, Rng& rng, std::string& kind);

// One mutation of a lattice .vti text.
std::string mutate_vti(const std::string& text, Rng& rng, std::string& kind);

// One mutation of a shock.csv text.
std::string mutate_csv(const std::string& text, Rng& rng, std::string& kind);

// A hostile file name (spaces, quotes, unicode, leading dash, very long).
std::string hostile_name(Rng& rng, const std::string& ext);

}  // namespace fuzz
