#pragma once
// A minimal reader of OpenFOAM ASCII output for two-dimensional cases (one
// cell thick, front and back faces in an `empty` patch): the mesh as cell
// polygons in the x-y plane, and cell fields of written times. Enough for the
// steady-state monitor and the resampling onto a lattice, with no OpenFOAM
// libraries linked. Binary or compressed files are InputError (the case
// templates write ASCII, uncompressed).
#include <array>
#include <string>
#include <vector>

#include "scene/vec2.hpp"

namespace cfd {

struct PatchInfo {
  std::string name;
  std::string type;  // patch, wall, symmetryPlane, empty, processor, ...
  long start = 0;
  long size = 0;
};

// A boundary face of the body patch, in the plane: centre, outward (from
// the fluid cell into the body) area vector per unit depth, fluid cell.
struct WallFace {
  scene::Vec2 centre;
  scene::Vec2 normal_area;  // |.| = edge length, points out of the fluid
  long cell = 0;
};

struct Mesh2D {
  std::vector<std::vector<scene::Vec2>> cell_polygons;  // counter-clockwise
  std::vector<double> cell_area;
  std::vector<scene::Vec2> cell_centre;
  // For each cell, the sum over its in-plane faces of (edge length,
  // normal) pairs: used for the free-stream Courant estimate.
  std::vector<std::vector<std::pair<double, scene::Vec2>>> cell_edges;
  std::vector<WallFace> body;  // faces of the patch named "body"
  std::vector<PatchInfo> patches;
  double depth = 1.0;          // extent in z
  std::size_t cells() const { return cell_area.size(); }
};

// Reads DIR/constant/polyMesh (DIR: a case or a processorN directory).
Mesh2D read_mesh_2d(const std::string& dir);

// internalField of a volScalarField / volVectorField file (uniform values are
// expanded to `cells` entries). InputError if missing or malformed.
std::vector<double> read_scalar_field(const std::string& path, std::size_t cells);
std::vector<std::array<double, 3>> read_vector_field(const std::string& path, std::size_t cells);

// Numeric time directories of DIR (excluding 0 unless include_zero), sorted.
struct TimeDir {
  double time = 0.0;
  std::string name;
};
std::vector<TimeDir> time_dirs(const std::string& dir, bool include_zero = false);

}  // namespace cfd
