// shockfit: locate the shock in a lattice field (granular or CFD) along body
// normals. A thin CLI over shockfit_core.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/group_fields.hpp"
#include "scene/progress.hpp"
#include "shockfit/group_interval.hpp"
#include "shockfit/locate.hpp"

int main(int argc, char** argv) {
  return scene::run_guarded("shockfit", [&]() -> int {
    CLI::App app{"Locate the shock in a lattice field (granular or CFD) by two-line fits along body normals.\n"
                 "Writes DIR/shock.csv, DIR/summary.json, DIR/shock.png and DIR/profile.png."};
    std::string scene_path, fields_path, out_dir, field, groups_path;
    app.add_option("scene", scene_path, "scene file (YAML)")->required();
    app.add_option("--fields", fields_path, "lattice fields (.vti) from granular or the CFD resampler")->required();
    app.add_option("--out", out_dir, "output directory")->required();
    app.add_option("--field", field, "field to fit (overrides shockfit.field): auto, density, volume_fraction, rho, number_density, v");
    app.add_option("--groups", groups_path,
                   "the averaging groups' fields (.vti, granular's groups.vti) for the interval; "
                   "default: groups.vti "
                   "beside --fields when there is one; 'none': the bootstrap over stations");
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
    // A lattice without a single finite value has no shock to find: that is
    // a bad input file, not an empty result.
    const bool any_finite = std::any_of(lat.fields.begin(), lat.fields.end(), [](const auto& kv) {
      return std::any_of(kv.second.begin(), kv.second.end(), [](double v) { return std::isfinite(v); });
    });
    if (!any_finite) throw scene::InputError(fields_path + ": every value of every field is NaN or infinite");
    // The locator's input errors are about this lattice: name its file.
    shockfit::ShockResult r = [&] {
      try {
        return shockfit::locate_shock(s, lat);
      } catch (const scene::InputError& e) {
        const std::string msg = e.what();
        if (msg.rfind(fields_path, 0) == 0 || msg.rfind(scene_path, 0) == 0) throw;
        throw scene::InputError(fields_path + ": " + msg);
      }
    }();
    if (lat.has(r.field)) {
      const auto& f = lat.field(r.field);
      if (std::none_of(f.begin(), f.end(), [](double v) { return std::isfinite(v); }))
        throw scene::InputError(fields_path + ": field '" + r.field + "' holds no finite value");
    }
    if (groups_path.empty()) {
      const auto beside = std::filesystem::path(fields_path).parent_path() / "groups.vti";
      if (std::filesystem::is_regular_file(beside)) groups_path = beside.string();
    }
    if (!groups_path.empty() && groups_path != "none") {
      if (!std::filesystem::is_regular_file(groups_path))
        throw scene::InputError(groups_path + ": groups file not found");
      const scene::Lattice packed = scene::read_vti(groups_path);
      if (packed.nx != lat.nx || packed.ny != lat.ny || packed.x0 != lat.x0 || packed.y0 != lat.y0)
        throw scene::InputError(groups_path + ": its lattice is not that of " + fields_path);
      shockfit::apply_group_interval(s, scene::unpack_groups(packed, groups_path), r);
    }
    shockfit::write_outputs(s, lat, r, out_dir);
    scene::log_line(
        "shockfit: " + s.name + ": shock " + scene::to_string(r.shock) + " (field " + r.field +
        ", " + std::to_string(r.accepted_count()) + " of " + std::to_string(r.stations.size()) +
        " stations accepted; 95% interval: " + r.interval_method +
        (r.interval_groups > 0 ? " over " + std::to_string(r.interval_groups) + " averaging groups"
                               : "") +
        ")");
    return 0;
  });
}
