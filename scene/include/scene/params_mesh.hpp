#pragma once
#include <optional>

namespace scene {

// `mesh:` section. Lengths in body lengths.
struct MeshParams {
  double h_min = 0.01;             // cell size in the shock band
  double h_max = 0.05;             // far-field cell size
  std::optional<double> band_width;  // half-width of the fine band; default from shock CI
  double growth = 1.2;             // bounded size ratio between neighbours
  std::optional<double> target_cells;  // if set, scales h_min/h_max to meet it within 10%
  bool recombine = true;           // quad-dominant
};

}  // namespace scene
