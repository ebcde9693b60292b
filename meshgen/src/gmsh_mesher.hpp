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

// A mesh edge on the region's boundary (two node indices) and its patch.
struct BoundaryEdge {
  int a = 0, b = 0;
  Patch patch = Patch::body;
};

// The 2D cells of the base plane z = 0 (the extruded grid has one cell per
// 2D cell): quads, and triangles with node[3] = -1, in gmsh's orientation
// (either sense); and the mesh edges on the region's boundary curves, each
// with the patch of its curve (edges on the strips' outlines are internal
// and not listed).
struct PlaneMesh {
  std::vector<scene::Vec2> nodes;
  std::vector<std::array<int, 4>> cells;
  std::vector<BoundaryEdge> boundary;
  long quads = 0, triangles = 0;
  int pieces = 1;         // surfaces the region was meshed as (region_split.hpp)
};

struct GmshJob {
  bool recombine = true;
  bool frontal = false;   // Frontal-Delaunay instead of Delaunay
  int smoothing = 0;      // Laplacian smoothing passes
  // pieces > 1: the region is cut into up to this many pieces where it can
  // be (region_split.hpp), which gmsh meshes on `threads` threads.
  int pieces = 1;
  int threads = 1;
  double thickness = 0.05;  // z-extent of the one-cell layer
  // When set, gmsh itself also extrudes the mesh one cell thick, names the
  // patches (physical surfaces inlet, outlet, top, bottom, body,
  // frontAndBack; volume "fluid") and writes it here in gmsh 2.2 ASCII: the
  // gmshToFoam route the direct polyMesh writer is tested against. meshgen
  // itself leaves it empty (poly_mesh.hpp, msh_writer.hpp write its outputs).
  std::string extruded_msh_path;
};

// Meshes the region in 2D with `size` as gmsh's size callback (and extrudes
// and writes the extruded .msh when job.extruded_msh_path is set).
// RunError when gmsh fails.
PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeField& size, const GmshJob& job);

// The same with shock-aligned strips (band_strip.hpp): each strip a
// transfinite surface of quads, the rest meshed round them with `size`.
using SizeFunction = std::function<double(scene::Vec2)>;
PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeFunction& size,
                         const std::vector<ShockStrip>& strips, const GmshJob& job);

}  // namespace meshgen
