#pragma once
// PNG plots through gnuplot (private to shockfit_core).
#include <string>

#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "shockfit/locate.hpp"

namespace shockfit {

// DIR/shock.png (field, stations, shock points, fitted shock) and
// DIR/profile.png (one station's profile and its two lines). Returns false,
// with the reason in `why`, when gnuplot is missing or fails; never throws
// for that.
bool write_plots(const scene::Scene& s, const scene::Lattice& lat, const ShockResult& r,
                 const std::string& out_dir, std::string& why);

}  // namespace shockfit
