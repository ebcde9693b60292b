#pragma once
#include <optional>
#include <string>

namespace scene {

// `mesh:` section (meshgen, docs/meshgen.md). Lengths in body lengths.
struct MeshParams {
  double h_min = 0.01;               // cell size in the shock band
  double h_max = 0.05;               // far-field cell size
  std::optional<double> band_width;  // half-width of the fine band; the shock's ci widens it
  double growth = 1.2;               // bounded size ratio between neighbouring cells
  std::optional<double> target_cells;  // if set, scales the sizes to meet it within 10%
  bool recombine = true;             // quad-dominant (triangles otherwise)
  std::optional<double> h_body;      // cell size at the body surface; default h_min (docs/meshgen.md)
  std::optional<double> h_uniform;   // cell size of the uniform grid; default h_min
  std::string algorithm = "delaunay";  // gmsh 2D algorithm: delaunay (fast) | frontal (better cells)
  int smoothing = 1;                 // gmsh Laplacian smoothing passes (~2 s CPU per 100k cells each)
  // Max along/across aspect of band cells; 1 = isotropic band; unset: the
  // body's default (scene::band_anisotropy).
  std::optional<double> anisotropy;
  bool extend_shock = true;          // carry the band along the shock's end tangents to the region's edge
  // Neither h_min nor h_max in the scene: `pipeline run` may coarsen both
  // together so the run's estimated cost fits pipeline.budget_cpu_seconds.
  // Not written back (a resolved scene states the sizes it ran with).
  bool sizes_default = false;
};

}  // namespace scene
