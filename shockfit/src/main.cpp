// shockfit: locate the shock in a lattice field (granular or CFD) along body
// normals. A thin CLI over shockfit_core.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/progress.hpp"
#include "shockfit/locate.hpp"

int main(int argc, char** argv) {
  return scene::run_guarded("shockfit", [&]() -> int {
    CLI::App app{"Locate the shock in a lattice field (granular or CFD) by two-line fits along body normals.\n"
                 "Writes DIR/shock.csv, DIR/summary.json, DIR/shock.png and DIR/profile.png."};
    std::string scene_path, fields_path, out_dir, field;
    app.add_option("scene", scene_path, "scene file (YAML)")->required();
    app.add_option("--fields", fields_path, "lattice fields (.vti) from granular or the CFD resampler")->required();
    app.add_option("--out", out_dir, "output directory")->required();
    app.add_option("--field", field, "field to fit (overrides shockfit.field): auto, density, volume_fraction, rho, number_density, v");
    app.set_version_flag("--version", scene::version_string());
    if (const auto code = scene::parse_cli(app, argc, argv)) return *code;
    scene::Scene s = scene::load_scene(scene_path);
    if (!field.empty()) {
      static const char* const kAllowed[] = {"auto", "density", "volume_fraction", "rho", "number_density", "v"};
      if (std::find(std::begin(kAllowed), std::end(kAllowed), field) == std::end(kAllowed))
        throw scene::InputError("--field '" + field + "': expected one of auto, density, volume_fraction, rho, number_density, v");
      s.shockfit.field = field;
    }
    if (!std::filesystem::is_regular_file(fields_path)) throw scene::InputError(fields_path + ": fields file not found");
    const scene::Lattice lat = scene::read_vti(fields_path);
    const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
    shockfit::write_outputs(s, lat, r, out_dir);
    scene::log_line("shockfit: " + s.name + ": shock " + r.shock + " (field " + r.field + ", " +
                    std::to_string(r.accepted_count()) + " of " + std::to_string(r.stations.size()) +
                    " stations accepted)");
    return 0;
  });
}
