#pragma once
// Sampling a lattice field along a body normal.
#include <string>
#include <vector>

#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "shockfit/two_line_fit.hpp"
#include "scene/vec2.hpp"

namespace shockfit {

struct Profile {
  std::vector<double> t;  // distance from the surface along the normal
  std::vector<double> f;  // field value
  double spacing = 0.0;   // lattice spacing measured along the normal
  double step = 0.0;      // distance between samples
};

// Lattice spacing along unit direction n (dx for n = x, dy for n = y).
double spacing_along(const scene::Lattice& lat, scene::Vec2 n);

// Bilinear samples of `field` from `origin` along unit `normal` to where the
// ray leaves the domain or the lattice, every half lattice spacing. Points
// are skipped where a neighbouring cell is inside the body (NaN field or
// inside_body > 0) or, when the lattice has `samples`, where the interpolated
// sample count is below min_samples.
Profile sample_profile(const scene::Lattice& lat, const std::string& field, const scene::Domain& d,
                       scene::Vec2 origin, scene::Vec2 normal, int min_samples);

// Two-line fit options for a profile: the shock window and the noise
// correlation in the profile's own units.
TwoLineOptions two_line_options(const Profile& p, const scene::ShockfitParams& params);

}  // namespace shockfit
