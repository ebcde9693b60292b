#pragma once
// meshgen: gmsh grids clustered at a predicted shock, and their uniform
// twins, written as gmsh and OpenFOAM meshes (docs/meshgen.md).
//
// gmsh is a process-global library: generate_mesh serialises its calls
// (one mesh at a time per process) and keeps gmsh initialised between them.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "scene/vec2.hpp"

namespace meshgen {

struct MeshRequest {
  bool uniform = false;
  std::vector<scene::Vec2> shock_curve;  // accepted shock points in order (scene coordinates)
  std::vector<double> shock_ci;          // 95% half-width per point along the normal; may be empty
  std::optional<double> h_min, h_max;    // override scene.mesh (body lengths); uniform: h_min is its size
  std::optional<double> target_cells;    // override scene.mesh.target_cells (wins over h_min/h_max)
  std::optional<double> h_body;          // override scene.mesh.h_body (body lengths; clustered and adapted)
  // An adapted grid instead of a clustered one: target sizes from the
  // lattice field "h" (body lengths), clamped to [h_min, h_max]; whatever
  // made them (size_field.hpp).
  std::shared_ptr<const scene::Lattice> size_field;
  std::string size_field_path;  // where it was read, for summary.json
};

struct MeshResult {
  std::string kind;  // clustered | uniform | adapted
  long cells = 0;
  double min_cell_size = 0, max_cell_size = 0;  // mean edge length of a cell, scene coordinates
  double max_non_orthogonality = 0, max_skewness = 0;  // checkMesh, degrees / -
  bool check_mesh_ok = false;
  double seconds = 0;  // gmsh: geometry, 2D meshing (all attempts' last), reading the plane mesh back
  nlohmann::json details;  // every other figure written to summary.json
  nlohmann::json summary() const;
};

// The checks generate_mesh makes before it writes anything (and before gmsh
// starts): a supersonic scene, finite sizes within range, and an estimated
// cell count within meshgen's limit (5e6; InputError with the estimate).
// Returns the estimated cell count.
double check_mesh_request(const scene::Scene& s, const MeshRequest& r);

// Writes OUT/mesh.msh, OUT/constant/polyMesh/ (written directly, no
// gmshToFoam), OUT/system/controlDict, OUT/log.checkMesh, OUT/summary.json and OUT/mesh.png,
// OUT/mesh_zoom.png (plots are best effort). InputError on a bad request
// (clustered without a shock curve, a shock wholly outside the flow),
// RunError when gmsh or OpenFOAM fail or a target count cannot be met.
MeshResult generate_mesh(const scene::Scene& s, const MeshRequest& r, const std::string& out_dir);

// Reads shock.csv (columns by name: shock_x, shock_y, accepted, optional
// ci). InputError on a missing or empty file, a missing column, a bad
// number, or no accepted rows.
MeshRequest request_from_shock_csv(const std::string& path);

// Reads a size field (a lattice .vti with a field "h", body lengths).
// InputError naming the file when it is missing or malformed, has no "h",
// or an h that is not finite and positive.
MeshRequest request_from_size_field(const std::string& path);

}  // namespace meshgen
