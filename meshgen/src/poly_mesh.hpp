#pragma once
// constant/polyMesh written directly from the plane mesh (private): one
// layer of hexahedra and prisms from z = 0 to z = thickness, the same grid
// gmshToFoam makes of gmsh's extrusion (tested against it), without the
// round trip through a 3D .msh file.
#include <optional>
#include <string>
#include <vector>

#include "extruded_layer.hpp"

namespace meshgen {

struct FoamPatch {
  std::string name;
  std::string type;            // patch, wall, symmetryPlane, empty
  std::optional<Patch> edges;  // the lateral faces over these edges; none: the front and back faces
};

// meshgen's patches in the order gmshToFoam gave them (so cases and logs
// compare alike with earlier grids): frontAndBack (empty), body (wall),
// outlet, top, inlet (patch), bottom (symmetryPlane on a symmetric domain).
std::vector<FoamPatch> foam_patches(bool symmetric);

// ASCII points, faces, owner, neighbour and boundary under
// CASE/constant/polyMesh: internal faces in upper-triangular order, then
// the patches in the order given. RunError when a patch of the layer is not
// in `patches`.
void write_poly_mesh(const PlaneMesh& m, const ExtrudedLayer& layer, double thickness,
                     const std::vector<FoamPatch>& patches, const std::string& case_dir);

}  // namespace meshgen
