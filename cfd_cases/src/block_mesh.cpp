#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "case_setup.hpp"
#include "cfd/run_case.hpp"
#include "foam_process.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace cfd {
namespace fs = std::filesystem;

namespace {
using scene::kDeg;
// The blockMesh domain ends where the wedge face does; a scene domain
// override must agree to this relative tolerance.
constexpr double kOutflowMatch = 1e-6;

const char* kControlDict = R"(FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    location    "system";
    object      controlDict;
}
// Only for blockMesh; the flow case has its own.
application     blockMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          1;
writeControl    timeStep;
writeInterval   1;
writeFormat     ascii;
writePrecision  12;
writeCompression off;
)";
}  // namespace

void make_wedge_block_mesh(const scene::Scene& s, long cells, const std::string& out_dir, double grading_y) {
  if (!s.body || !scene::straight_ramp_length(*s.body))
    throw scene::InputError(s.source_file + ": cfd blockmesh makes wedge grids only (body.kind: wedge)");
  const double th = s.body->angle_deg * kDeg;
  if (!scene::oblique_shock_beta(s.freestream.mach, th, s.freestream.gamma))
    throw scene::InputError(s.source_file + ": the shock is detached at this Mach number; blockmesh covers attached wedges");
  if (cells < 10) throw scene::InputError("cfd blockmesh: --cells must be at least 10");
  if (!(grading_y > 0)) throw scene::InputError("cfd blockmesh: --grading must be positive");
  const scene::Domain d = scene::scene_domain(s);
  const double xe = s.body->length * std::cos(th), ye = s.body->length * std::sin(th);
  if (std::abs(d.xmax - xe) > kOutflowMatch * s.body->length)
    throw scene::InputError(s.source_file + ": domain: xmax must be the wedge's rear end for blockmesh");
  const double area = -d.xmin * d.ymax + xe * (d.ymax - 0.5 * ye);
  const double h = std::sqrt(area / static_cast<double>(cells));
  const auto count = [h](double len) { return std::max(1L, std::lround(len / h)); };
  const std::map<std::string, std::string> v{
      {"XMIN", fmt::format("{:.12g}", d.xmin)},  {"XE", fmt::format("{:.12g}", xe)},
      {"YE", fmt::format("{:.12g}", ye)},        {"YMAX", fmt::format("{:.12g}", d.ymax)},
      {"DEPTH", fmt::format("{:.12g}", h)},      {"NX_UP", std::to_string(count(-d.xmin))},
      {"NX_BODY", std::to_string(count(xe))},    {"NY", std::to_string(count(d.ymax - 0.5 * ye))},
      {"GRADING_Y", fmt::format("{:.12g}", grading_y)}};
  const std::string tpl = template_dir() + "/blockMesh/system/blockMeshDict";
  scene::make_dirs(out_dir + "/system");
  scene::write_file_atomic(out_dir + "/system/blockMeshDict", fill_placeholders(scene::read_file(tpl), v, tpl));
  scene::write_file_atomic(out_dir + "/system/controlDict", kControlDict);
  fs::remove_all(fs::path(out_dir) / "constant/polyMesh");
  run_foam(fs::weakly_canonical(out_dir).string(), "blockMesh", {});
}

}  // namespace cfd
