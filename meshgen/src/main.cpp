// meshgen: gmsh grid clustered at a predicted shock, or its uniform twin.
//   meshgen SCENE.yaml --shock shock.csv --out DIR
//   meshgen SCENE.yaml --uniform --out DIR
//   meshgen SCENE.yaml --size-field FIELD.vti [--h-min H] --out DIR
// Writes DIR/mesh.msh, DIR/constant/polyMesh, DIR/summary.json, DIR/mesh*.png.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "meshgen/mesh.hpp"
#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/staging.hpp"

int main(int argc, char** argv) {
  CLI::App app{"meshgen: gmsh grid clustered at the predicted shock (or uniform), written for OpenFOAM"};
  std::string scene_path, shock_path, size_field_path, out_dir;
  bool uniform = false, dry_run = false;
  std::optional<double> h_min, h_max, target;
  app.add_option("scene", scene_path, "scene file (YAML)")->required();
  app.add_option("--shock", shock_path, "shock.csv from shockfit (columns shock_x, shock_y, accepted[, ci])");
  app.add_option("--size-field", size_field_path,
                 "adapted grid: lattice .vti with a field h, the target cell size (body lengths), clamped to "
                 "[h_min, h_max]");
  app.add_flag("--uniform", uniform, "one cell size everywhere (mesh.h_uniform, default mesh.h_min)");
  app.add_option("--out", out_dir, "output folder")->required();
  // CLI11's PositiveNumber lets nan and inf through: ask for finite values.
  const auto finite_positive = CLI::Validator(
      [](std::string& v) -> std::string {
        double d = 0;
        if (!CLI::detail::lexical_cast(v, d) || !std::isfinite(d) || !(d > 0))
          return "expected a finite positive number, got '" + v + "'";
        return {};
      },
      "FINITE>0");
  app.add_option("--h-min", h_min, "override mesh.h_min (body lengths); for --uniform: the cell size")
      ->check(finite_positive);
  app.add_option("--h-max", h_max, "override mesh.h_max (body lengths)")->check(finite_positive);
  app.add_option("--target-cells", target, "override mesh.target_cells (met within 10%)")->check(finite_positive);
  app.add_flag("--dry-run", dry_run, "validate the scene and shock file, print the resolved scene, mesh nothing");
  app.set_version_flag("--version", scene::version_string());
  if (const auto code = scene::parse_cli(app, argc, argv)) return *code;
  scene::install_interrupt_handler();
  return scene::run_guarded("meshgen", [&]() -> int {
    const scene::Scene s = scene::load_scene(scene_path);
    scene::require_supersonic(s, "meshgen");
    scene::refuse_out_overlap(out_dir, scene_path, "scene file");
    meshgen::MeshRequest req;
    if (static_cast<int>(!shock_path.empty()) + static_cast<int>(!size_field_path.empty()) + static_cast<int>(uniform) > 1)
      throw scene::InputError("give one of --shock, --size-field and --uniform");
    if (!shock_path.empty()) req = meshgen::request_from_shock_csv(shock_path);
    else if (!size_field_path.empty()) req = meshgen::request_from_size_field(size_field_path);
    else if (!uniform)
      throw scene::InputError("a clustered grid needs --shock shock.csv (or --size-field FIELD.vti, or --uniform)");
    req.uniform = uniform;
    req.h_min = h_min;
    req.h_max = h_max;
    req.target_cells = target;
    if (dry_run) {
      const double estimate = meshgen::check_mesh_request(s, req);
      std::cout << scene::to_yaml(s) << "# shock points: " << req.shock_curve.size() << "\n"
                << "# estimated cells: " << static_cast<long>(estimate) << "\n";
      return 0;
    }
    const meshgen::MeshResult r = meshgen::generate_mesh(s, req, out_dir);
    if (const auto dropped = r.details.find("strips_dropped");
        dropped != r.details.end() && dropped->is_string())
      std::cerr << "meshgen: warning: gmsh could not mesh round the shock-aligned strips ("
                << dropped->get<std::string>() << "); the band was meshed isotropically\n";
    std::cout << "meshgen: " << r.kind << " grid, " << r.cells << " cells, h " << r.min_cell_size << " .. "
              << r.max_cell_size << ", max non-orthogonality " << r.max_non_orthogonality << ", max skewness "
              << r.max_skewness << ", checkMesh " << (r.check_mesh_ok ? "OK" : "FAILED") << ", gmsh " << r.seconds
              << " s -> " << out_dir << "\n";
    return 0;
  });
}
