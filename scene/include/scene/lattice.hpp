#pragma once
// A uniform 2D lattice of named scalar fields, cell-centred, in scene
// coordinates. One writer and one reader: VTK ImageData (.vti), CellData.
#include <map>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace scene {

struct Lattice {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0;  // lower-left corner of cell (0, 0)
  double dx = 1, dy = 1;
  std::map<std::string, std::vector<double>> fields;  // each nx*ny, index i + nx*j

  Lattice() = default;
  Lattice(int nx_, int ny_, double x0_, double y0_, double dx_, double dy_);

  std::vector<double>& add(const std::string& name, double value = 0.0);
  const std::vector<double>& field(const std::string& name) const;  // InputError if missing
  bool has(const std::string& name) const { return fields.count(name) != 0; }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(i + nx * j); }
  double xc(int i) const { return x0 + (i + 0.5) * dx; }
  double yc(int j) const { return y0 + (j + 0.5) * dy; }
  // Bilinear interpolation between cell centres; false outside or when a
  // neighbour is NaN (e.g. inside the body).
  bool sample(const std::string& name, double x, double y, double& out) const;
};

// An nx x ny lattice spanning the domain: the one grid granular fields, CFD
// resampling and shockfit share.
Lattice domain_lattice(const Domain& d, int nx, int ny);

void write_vti(const Lattice& lat, const std::string& path);  // atomic
Lattice read_vti(const std::string& path);                     // InputError on bad files

}  // namespace scene
