#pragma once
#include <cstdint>
#include <string>

namespace scene {

// `shockfit:` section.
struct ShockfitParams {
  int stations = 40;               // normals along the body surface
  std::string field = "auto";      // auto | volume_fraction | density | v | rho
  int min_samples = 10;            // lattice cells with fewer samples are skipped
  double noise_factor = 3.0;       // a jump must exceed this many noise sigmas
  int bootstrap = 400;             // resamples for the 95% interval
  std::uint64_t seed = 1;
};

}  // namespace scene
