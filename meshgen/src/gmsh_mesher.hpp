#pragma once
// The gmsh part of meshgen (private: gmsh types stay in gmsh_mesher.cpp).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "meshgen/fluid_region.hpp"
#include "band_strip.hpp"
#include "meshgen/size_field.hpp"

namespace meshgen {

// The 2D cells of the base plane z = 0 (the extruded grid has one cell per
// 2D cell): quads, and triangles with node[3] = -1.
struct PlaneMesh {
  std::vector<scene::Vec2> nodes;
  std::vector<std::array<int, 4>> cells;
  long quads = 0, triangles = 0;
  long volume_cells = 0;  // hexahedra + prisms after extrusion
};

struct GmshJob {
  bool recombine = true;
  bool frontal = false;   // Frontal-Delaunay instead of Delaunay
  int smoothing = 0;      // Laplacian smoothing passes
  double thickness = 0.05;  // z-extent of the one-cell layer
  std::string msh_path;     // written in gmsh 2.2 ASCII (what gmshToFoam reads)
};

// Meshes the region with `size` as gmsh's size callback, extrudes it one
// cell thick, names the patches (physical surfaces inlet, outlet, top,
// bottom, body, frontAndBack; volume "fluid") and writes the .msh file.
// RunError when gmsh fails.
PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeField& size, const GmshJob& job);

// The same with shock-aligned strips (band_strip.hpp): each strip a
// transfinite surface of quads, the rest meshed round them with `size`.
using SizeFunction = std::function<double(scene::Vec2)>;
PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeFunction& size,
                         const std::vector<ShockStrip>& strips, const GmshJob& job);

}  // namespace meshgen
