#pragma once
// The one-cell-thick layer over a plane mesh (private), as topology: cells
// counter-clockwise, each mesh edge a lateral face with its owner and
// neighbour, boundary edges grouped by patch. Both grid writers (poly_mesh,
// msh_writer) extrude from it, so they agree face for face.
#include <array>
#include <vector>

#include "gmsh_mesher.hpp"

namespace meshgen {

// The lateral face over mesh edge a -> b, traversed as in the owner's
// counter-clockwise outline: (a, b, b', a') with ' the node at z =
// thickness has its area vector pointing out of the owner.
struct LayerFace {
  int owner = 0;
  int neighbour = -1;  // -1 on the boundary
  int a = 0, b = 0;
};

inline constexpr int kPatchCount = 5;  // Patch::inlet .. Patch::body

struct ExtrudedLayer {
  std::vector<std::array<int, 4>> cells;  // counter-clockwise; node[3] = -1 for triangles
  std::vector<LayerFace> internal;        // sorted by owner, then neighbour (OpenFOAM's order)
  std::array<std::vector<LayerFace>, kPatchCount> boundary;  // by static_cast<int>(Patch)
};

// RunError when a cell has no area, an edge has more than two cells or two
// cells traversing it the same way (overlap), or a boundary edge has no
// patch (or a patch edge is not on the boundary).
ExtrudedLayer extrude_layer(const PlaneMesh& m);

inline int corner_count(const std::array<int, 4>& c) {
  return c[3] < 0 ? 3 : 4;
}

}  // namespace meshgen
