#pragma once
// mesh.msh written from the extruded layer (private): gmsh 2.2 ASCII with
// the same content gmsh's own extrusion wrote (hexahedra and prisms of the
// one-cell layer, physical surfaces inlet, outlet, top, bottom, body,
// frontAndBack and volume "fluid"), so users can open the grid in gmsh.
#include <string>

#include "extruded_layer.hpp"

namespace meshgen {

void write_extruded_msh(const PlaneMesh& m, const ExtrudedLayer& layer, double thickness,
                        const std::string& path);

}  // namespace meshgen
