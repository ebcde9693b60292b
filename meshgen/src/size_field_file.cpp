// A size field file -> MeshRequest: a lattice .vti whose field "h" is the
// target cell size in body lengths, checked whole before anything is meshed.
#include <cmath>
#include <filesystem>

#include "meshgen/mesh.hpp"
#include "scene/errors.hpp"
#include "scene/lattice.hpp"

namespace meshgen {

MeshRequest request_from_size_field(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw scene::InputError(path + ": size field: no such file");
  auto lat = std::make_shared<scene::Lattice>(scene::read_vti(path));
  if (!lat->has("h"))
    throw scene::InputError(path + ": size field: no field 'h' (target cell size, body lengths)");
  const std::vector<double>& h = lat->field("h");
  for (int j = 0; j < lat->ny; ++j)
    for (int i = 0; i < lat->nx; ++i) {
      const double v = h[lat->index(i, j)];
      if (!std::isfinite(v) || !(v > 0))
        throw scene::InputError(path + ": size field: h must be finite and positive, got " +
                                std::to_string(v) + " at cell (" + std::to_string(i) + ", " +
                                std::to_string(j) + ")");
    }
  MeshRequest r;
  r.size_field = std::move(lat);
  r.size_field_path = path;
  return r;
}

}  // namespace meshgen
