#pragma once
#include <cstdint>
#include <string>

namespace scene {

// `shockfit:` section (docs/shockfit.md).
struct ShockfitParams {
  int stations = 40;               // normals along the body surface
  std::string field = "auto";      // auto | density | volume_fraction | rho | number_density | v
  int min_samples = 10;            // lattice cells with fewer samples are skipped
  double noise_factor = 3.0;       // a jump must exceed this many noise sigmas
  int bootstrap = 400;             // resamples for the 95% interval
  std::uint64_t seed = 1;
  double window = 4.0;             // half-width of the shock window, in lattice spacings
};

}  // namespace scene
