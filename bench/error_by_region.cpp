// Where a blunt body's forebody total-enthalpy error lives: the L1 sum of
// |h0/h0_inf - 1| (the verdict's primary measure on bodies without an exact
// field) split by distance from the body and by cell size, for recorded
// CFD cases. Tells whether a grid family's error is in its shock band, its
// shock layer or its coarse cells.
//
//   error_by_region SCENE.yaml CASE_DIR...
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cfd/foam_reader.hpp"
#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"

namespace {

// Distance bands from the body surface, in body lengths.
constexpr std::array<double, 6> kDistanceEdges{0.0, 0.05, 0.15, 0.3, 0.5, 1e300};
// Cell sizes (square root of the area) in units of the smallest cell.
constexpr std::array<double, 5> kSizeEdges{0.0, 1.5, 3.0, 6.0, 1e300};

template <std::size_t N>
std::size_t bin_of(const std::array<double, N>& edges, double v) {
  for (std::size_t i = 0; i + 1 < N; ++i)
    if (v < edges[i + 1]) return i;
  return N - 2;
}

void report(const scene::Scene& s, const scene::BodyGeometry& g, const std::string& dir) {
  const auto times = cfd::time_dirs(dir);
  if (times.empty()) throw scene::RunError(dir + ": no written solution");
  const cfd::Mesh2D mesh = cfd::read_mesh_2d(dir);
  const std::string t = dir + "/" + times.back().name;
  const auto rho = cfd::read_scalar_field(t + "/rho", mesh.cells());
  const auto p = cfd::read_scalar_field(t + "/p", mesh.cells());
  const auto u = cfd::read_vector_field(t + "/U", mesh.cells());
  const double gamma = s.freestream.gamma, mach = s.freestream.mach;
  const double h_inf = 1.0 / (gamma - 1.0) + 0.5 * mach * mach;
  const double x_fore = scene::widest_section_x(g), L = g.length;

  double h_small = 1e300;
  for (std::size_t c = 0; c < mesh.cells(); ++c)
    h_small = std::min(h_small, std::sqrt(std::abs(mesh.cell_area[c])));

  constexpr std::size_t nd = kDistanceEdges.size() - 1, ns = kSizeEdges.size() - 1;
  std::array<std::array<double, ns>, nd> sum{}, area{};
  double total = 0, total_area = 0;
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    const auto x = mesh.cell_centre[c];
    if (x.x > x_fore) continue;
    const double a = std::abs(mesh.cell_area[c]);
    const double h0 =
        gamma * p[c] / ((gamma - 1.0) * rho[c]) + 0.5 * (u[c][0] * u[c][0] + u[c][1] * u[c][1]);
    const double err = std::abs(h0 / h_inf - 1.0) * a;
    const std::size_t i = bin_of(kDistanceEdges, scene::signed_distance(g, x) / L);
    const std::size_t j = bin_of(kSizeEdges, std::sqrt(a) / h_small);
    sum[i][j] += err;
    area[i][j] += a;
    total += err;
    total_area += a;
  }
  std::printf("%s  (%zu cells, time %s, smallest cell %.4g L)\n", dir.c_str(), mesh.cells(),
              times.back().name.c_str(), h_small / L);
  std::printf(
      "  forebody L1 total enthalpy %.5f; share of it by distance from the body (rows, L) and cell "
      "size "
      "(columns, smallest cells)\n",
      total / total_area);
  std::printf("  %-12s", "d \\ size");
  for (std::size_t j = 0; j < ns; ++j) std::printf("  <%-8.3g", kSizeEdges[j + 1]);
  std::printf("  | L1 contribution, area share\n");
  for (std::size_t i = 0; i < nd; ++i) {
    std::printf("  <%-11.3g", kDistanceEdges[i + 1]);
    double row = 0, row_area = 0;
    for (std::size_t j = 0; j < ns; ++j) {
      std::printf("  %-9.4f", total > 0 ? sum[i][j] / total : 0.0);
      row += sum[i][j];
      row_area += area[i][j];
    }
    std::printf("  | %.5f, %.3f\n", row / total_area, row_area / total_area);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: error_by_region SCENE.yaml CASE_DIR...\n");
    return 2;
  }
  try {
    const scene::Scene s = scene::load_scene(argv[1]);
    if (!s.body) throw scene::InputError(std::string(argv[1]) + ": the scene has no body");
    const auto g = scene::make_body(*s.body);
    for (int k = 2; k < argc; ++k) report(s, g, argv[k]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error_by_region: %s\n", e.what());
    return 1;
  }
  return 0;
}
