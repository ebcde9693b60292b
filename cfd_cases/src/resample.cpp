#include <algorithm>
#include <cmath>

#include "case_setup.hpp"
#include "cfd/foam_reader.hpp"
#include "cfd/run_case.hpp"
#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/units.hpp"

namespace cfd {

namespace {
bool in_polygon(const std::vector<scene::Vec2>& poly, scene::Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const scene::Vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}
}  // namespace

scene::Lattice resample_to_lattice(const scene::Scene& s, const std::string& case_dir, int nx, int ny) {
  if (!s.body) throw scene::InputError(s.source_file + ": resampling needs a scene with a body");
  if (nx < 1 || ny < 1) throw scene::InputError("resample: lattice size must be positive");
  const auto times = time_dirs(case_dir);
  if (times.empty()) throw scene::InputError(case_dir + ": no written solution time to resample");
  const std::string tdir = case_dir + "/" + times.back().name;
  const Mesh2D m = read_mesh_2d(case_dir);
  const auto rho = read_scalar_field(tdir + "/rho", m.cells());
  const auto p = read_scalar_field(tdir + "/p", m.cells());
  const auto T = read_scalar_field(tdir + "/T", m.cells());
  const auto U = read_vector_field(tdir + "/U", m.cells());

  scene::Lattice lat = scene::domain_lattice(scene::scene_domain(s), nx, ny);
  auto& f_rho = lat.add("rho", scene::kNaN);
  auto& f_u = lat.add("u", scene::kNaN);
  auto& f_v = lat.add("v", scene::kNaN);
  auto& f_p = lat.add("p", scene::kNaN);
  auto& f_T = lat.add("T", scene::kNaN);
  auto& f_mach = lat.add("mach", scene::kNaN);
  auto& inside = lat.add("inside_body", 0.0);
  const scene::BodyGeometry g = scene::make_body(*s.body);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (scene::point_in_body(g, {lat.xc(i), lat.yc(j)})) inside[lat.index(i, j)] = 1.0;

  // Piecewise constant: each lattice centre takes the value of the mesh cell
  // that contains it (first found on a shared edge).
  std::vector<char> done(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
  for (std::size_t c = 0; c < m.cells(); ++c) {
    const auto& poly = m.cell_polygons[c];
    double x0 = poly[0].x, x1 = x0, y0 = poly[0].y, y1 = y0;
    for (const auto& q : poly) {
      x0 = std::min(x0, q.x);
      x1 = std::max(x1, q.x);
      y0 = std::min(y0, q.y);
      y1 = std::max(y1, q.y);
    }
    const int i0 = std::max(0, static_cast<int>(std::floor((x0 - lat.x0) / lat.dx - 0.5)));
    const int i1 = std::min(nx - 1, static_cast<int>(std::ceil((x1 - lat.x0) / lat.dx - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor((y0 - lat.y0) / lat.dy - 0.5)));
    const int j1 = std::min(ny - 1, static_cast<int>(std::ceil((y1 - lat.y0) / lat.dy - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t k = lat.index(i, j);
        if (done[k] || inside[k] != 0.0 || !in_polygon(poly, {lat.xc(i), lat.yc(j)})) continue;
        done[k] = 1;
        f_rho[k] = rho[c];
        f_u[k] = U[c][0];
        f_v[k] = U[c][1];
        f_p[k] = p[c];
        f_T[k] = T[c];
        // c = sqrt(gamma R T) = sqrt(T) with R = 1/gamma.
        f_mach[k] = std::hypot(U[c][0], U[c][1]) / std::sqrt(T[c]);
      }
  }
  return lat;
}

}  // namespace cfd
