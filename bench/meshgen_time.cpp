// meshgen timing: every case-study body meshed at a target of N cells
// (default 100000), clustered (round a synthetic predicted shock: exact
// oblique shock for wedges, Billig's shape for blunt bodies) and uniform.
// Prints one row per grid: cells, gmsh wall and CPU seconds for the final
// mesh (geometry, 2D meshing), whole-run wall seconds (target iterations,
// polyMesh and mesh.msh writing, checkMesh, plots) and checkMesh figures.
//   build/bench/meshgen_time [N] [repeats] [case]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "meshgen/mesh.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"

namespace {

constexpr double kBenchCi = 0.02;  // band half-width from ci, body lengths

std::vector<scene::Vec2> predicted_shock(const scene::Scene& s) {
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  const double m = s.freestream.mach;
  std::vector<scene::Vec2> out;
  constexpr int kPoints = 40;
  if (const auto attached = scene::attached_shock_beta(s)) {
    const double beta = *attached;
    for (int i = 0; i < kPoints; ++i) {
      const double x = 1.2 * d.xmax * i / (kPoints - 1);
      out.push_back({x, x * std::tan(beta)});
    }
    return out;
  }
  double h = 0.0, xfront = g.polyline.front().x;
  for (const scene::Vec2 p : g.polyline) { h = std::max(h, p.y); xfront = std::min(xfront, p.x); }
  const double vertex = xfront - scene::billig_standoff_cylinder(m) * h;
  for (int i = 0; i < kPoints; ++i) {
    const double y = 1.1 * d.ymax * i / (kPoints - 1);
    out.push_back({vertex + scene::billig_shock_x(m, h, y), y});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const double target = argc > 1 ? std::atof(argv[1]) : 1e5;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 1;
  const std::string only = argc > 3 ? argv[3] : "";
  const std::string root = std::string(SOURCE_DIR) + "/pipeline/cases/";
  const auto out = std::filesystem::temp_directory_path() / "meshgen_bench";
  std::printf("%-12s %-9s %8s %9s %9s %9s %8s %8s %6s %8s\n", "case", "kind", "cells", "gmsh_wall",
              "run_cpu", "run_wall", "non_orth", "skew", "ok", "attempts");
  for (const char* name : {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"}) {
    if (!only.empty() && only != name) continue;
    const scene::Scene s = scene::load_scene(root + name + ".yaml");
    for (const bool uniform : {false, true}) {
      meshgen::MeshRequest r;
      r.uniform = uniform;
      r.shock_curve = predicted_shock(s);
      r.shock_ci.assign(r.shock_curve.size(), kBenchCi * scene::body_length(*s.body));
      r.target_cells = target;
      for (int k = 0; k < repeats; ++k) {
        const meshgen::MeshResult m = meshgen::generate_mesh(s, r, (out / name / (uniform ? "u" : "c")).string());
        std::printf("%-12s %-9s %8ld %9.2f %9.2f %9.2f %8.1f %8.2f %6s %8d\n", name, m.kind.c_str(),
                    m.cells, m.seconds, m.details.value("cpu_seconds", 0.0),
                    m.details.value("seconds_total", 0.0), m.max_non_orthogonality, m.max_skewness,
                    m.check_mesh_ok ? "yes" : "NO", m.details.value("mesh_attempts", 0));
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
