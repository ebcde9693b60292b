// cfd: OpenFOAM rhoCentralFoam cases for a scene (see docs/cfd_cases.md).
//   cfd run SCENE.yaml --mesh MESHDIR --out CASEDIR [--np N] [--lts|--no-lts]
//   cfd blockmesh SCENE.yaml --cells 5000 --out MESHDIR     (wedge grids without meshgen)
//   cfd resample SCENE.yaml --case CASEDIR --out FILE.vti [--nx 300] [--ny 0]
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cfd/run_case.hpp"
#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "scene/staging.hpp"

namespace {
constexpr int kDefaultLatticeNx = 300;

// ny from the domain's aspect ratio when not given.
int lattice_ny(const scene::Scene& s, int nx, int ny) {
  if (ny > 0) return ny;
  const scene::Domain d = scene::scene_domain(s);
  return std::max(1, static_cast<int>(std::lround(nx * d.height() / d.width())));
}
// The failed case moves from the staging folder to OUT.failed: the paths in
// its message (the log to read) must follow it.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cfd: OpenFOAM rhoCentralFoam cases for a scene, run to a measured steady state"};
  app.set_version_flag("--version", scene::version_string());
  app.require_subcommand(1);
  std::string scene_path, mesh_dir, out, case_dir;
  int np = 1, nx = kDefaultLatticeNx, ny = 0;
  long cells = 5000;
  double grading = 1.0;
  std::optional<double> lts_smoothing;
  bool lts = false, no_lts = false;

  CLI::App* run = app.add_subcommand("run", "instantiate the case in --out, run it to a steady state, write "
                                            "summary.json, history.csv/png and lattice.vti there");
  run->add_option("scene", scene_path, "scene YAML file")->required();
  run->add_option("--mesh", mesh_dir, "directory with constant/polyMesh (meshgen or cfd blockmesh output)")->required();
  run->add_option("--out", out, "case directory (replaced if it is an earlier case)")->required();
  run->add_option("--np", np, "MPI ranks (decomposePar, mpirun, reconstructPar)")->check(CLI::Range(1, 4096));
  auto* lts_flag = run->add_flag("--lts", lts, "local time stepping (ddt localEuler)");
  run->add_flag("--no-lts", no_lts, "time-accurate stepping")->excludes(lts_flag);
  run->add_option("--lts-smoothing", lts_smoothing,
                  "LTS rDeltaTSmoothingCoeff: how much a cell's local step may exceed its "
                  "neighbour's")
      ->check(CLI::PositiveNumber);
  run->add_option("--nx", nx, "lattice.vti cells along x")->check(CLI::Range(1, 100000));
  run->add_option("--ny", ny, "lattice.vti cells along y (default: from the domain's aspect ratio)")
      ->check(CLI::Range(0, 100000));

  CLI::App* bm = app.add_subcommand("blockmesh", "uniform blockMesh grid of a wedge scene (upper half) in --out");
  bm->add_option("scene", scene_path, "scene YAML file (attached-shock wedge)")->required();
  bm->add_option("--cells", cells, "approximate number of cells")->check(CLI::Range(10L, 100000000L));
  bm->add_option("--grading", grading, "blockMesh expansion ratio across the domain height")
      ->check(CLI::PositiveNumber);
  bm->add_option("--out", out, "output directory (gets constant/polyMesh)")->required();

  CLI::App* rs = app.add_subcommand("resample", "resample the latest time of a case onto a lattice (.vti)");
  rs->add_option("scene", scene_path, "scene YAML file")->required();
  rs->add_option("--case", case_dir, "case directory")->required();
  rs->add_option("--out", out, "output .vti file")->required();
  rs->add_option("--nx", nx, "lattice cells along x")->check(CLI::Range(1, 100000));
  rs->add_option("--ny", ny, "lattice cells along y (default: from the aspect ratio)")->check(CLI::Range(0, 100000));

  if (const auto code = scene::parse_cli(app, argc, argv)) return *code;
  return scene::run_guarded("cfd", [&]() -> int {
    const scene::Scene s = scene::load_scene(scene_path);
    if (bm->parsed()) {
      cfd::make_wedge_block_mesh(s, cells, out, grading);
      return 0;
    }
    if (rs->parsed()) {
      scene::write_vti(cfd::resample_to_lattice(s, case_dir, nx, lattice_ny(s, nx, ny)), out);
      return 0;
    }
    scene::require_supersonic(s, "cfd run");
    scene::refuse_out_overlap(out, mesh_dir, "--mesh folder");
    scene::refuse_out_overlap(out, scene_path, "scene file");
    scene::install_interrupt_handler();
    cfd::CaseOptions o;
    o.np = np;
    if (lts) o.local_time_stepping = true;
    if (no_lts) o.local_time_stepping = false;
    // The case is built beside --out and swapped in only when it finished:
    // a failed or interrupted run keeps the previous good case in --out and
    // leaves its own beside it as OUT.failed for inspection.
    o.lts_smoothing = lts_smoothing;
    scene::StagedDir staged(out);
    cfd::CaseResult r;
    try {
      r = cfd::run_case_with_fallback(s, mesh_dir, staged.path(), o);
      scene::write_vti(cfd::resample_to_lattice(s, r.case_dir, nx, lattice_ny(s, nx, ny)),
                       r.case_dir + "/lattice.vti");
    } catch (const scene::RunError& e) {
      const std::string stage = r.case_dir.empty() ? staged.path() : r.case_dir;
      const std::string kept = staged.keep_as(".failed");
      throw scene::RunError(replace_all(e.what(), stage, kept) + " (" + out + " is unchanged)");
    }
    staged.commit(scene::Leftovers::discard);
    // The case was written in the staging folder: its summary must name
    // where the case now lives, or a reader follows a path that is gone.
    r.case_dir = out;
    r.history_csv = out + "/history.csv";
    scene::write_json_atomic(out + "/summary.json", r.summary());
    std::cout << r.summary().dump(2) << "\n";
    return 0;
  });
}
