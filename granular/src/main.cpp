// granular: event-driven granular gas runs for one scene.
//   granular run SCENE.yaml --out DIR [--np N] [--dry-run]
// Box scenes (validation) go to run_box_scene, body scenes to run_flow_scene.
// Under `mpirun -np N granular run ...` the replicas of a body scene are
// spread over the ranks and reduced into one field file written by rank 0.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <algorithm>
#include <filesystem>
#include <optional>
#include <unistd.h>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#ifdef GRANULAR_HAVE_MPI
#include <mpi.h>
#endif

#include "granular/box_run.hpp"
#include "granular/flow_run.hpp"
#include "granular/flow_setup.hpp"
#include "scene/cli.hpp"
#include "scene/cli_parse.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/staging.hpp"

namespace {


#ifdef GRANULAR_HAVE_MPI
// MPI lifetime as a value: initialised only when the launcher started us
// under mpirun (or always harmlessly as a singleton), finalised on exit.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

granular::ReplicaGroup mpi_group(const MpiSession& mpi) {
  granular::ReplicaGroup g;
  g.rank = mpi.rank();
  g.size = mpi.size();
  g.sum = [](std::vector<double>& v) {
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM,
                  MPI_COMM_WORLD);
  };
  g.any = [](bool flag) {
    int local = flag ? 1 : 0, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return global != 0;
  };
  return g;
}
#endif

// Several ranks on one machine already share its cores.
int default_threads(int ranks) {
  if (ranks > 1) return 1;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void print_dry_run(const scene::Scene& s) {
  std::cout << scene::to_yaml(s);
  if (s.body) {
    const granular::FlowSetup f = granular::make_flow_setup(s);
    std::cout << "# granular flow (lengths in particle diameters):\n"
              << granular::describe(f).dump(2) << "\n";
  }
}

// A complete run replaces OUT. An interrupted one must not replace complete
// results: when OUT already holds some, the partial ones go beside it as
// OUT.partial (their summary says "partial": true); with nothing to lose
// they become OUT. Returns the exit code; RunError for an interrupted flow.
int finish_run(scene::StagedDir& staged, const nlohmann::json& summary) {
  const bool partial = summary.value("partial", summary.value("interrupted", false));
  if (!partial) {
    staged.commit(scene::Leftovers::discard);
    return 0;
  }
  std::error_code ec;
  const bool has_results = std::filesystem::exists(staged.out() + "/summary.json", ec);
  const std::string where = has_results ? staged.keep_as(".partial") : staged.out();
  if (!has_results) staged.commit(scene::Leftovers::discard);
  const std::string kept = has_results ? "; the complete results in " + staged.out() + " are unchanged" : "";
  if (summary.value("kind", "") != "flow") {
    // Box runs stop cleanly on Ctrl-C with a summary of what they did.
    std::fprintf(stderr, "granular: interrupted: partial summary in %s%s\n", where.c_str(), kept.c_str());
    return 0;
  }
  throw scene::RunError("interrupted: the fields averaged so far are in " + where + " (partial)" + kept);
}

}  // namespace

int main(int argc, char** argv) {
#ifdef GRANULAR_HAVE_MPI
  const MpiSession mpi(argc, argv);
  const int rank = mpi.rank();
  const int ranks = mpi.size();
#else
  const int rank = 0;
  const int ranks = 1;
#endif
  CLI::App app{"granular: event-driven granular gas (hard disks) past a scene body, or in a box"};
  app.set_version_flag("--version", scene::version_string());
  app.require_subcommand(1);
  std::string scene_path, out_dir;
  int np = 0;  // 0: one thread per core (one per rank under mpirun)
  bool dry_run = false;
  CLI::App* run = app.add_subcommand("run", "run one scene and write DIR/fields.vti (body scenes) and DIR/summary.json");
  run->add_option("scene", scene_path, "scene YAML file")->required();
  run->add_option("--out", out_dir, "output directory");
  run->add_option("--np", np,
                  "replicas run at once in threads, per MPI rank (default: one per core; 1 under mpirun)")
      ->check(CLI::Range(1, 1024));
  run->add_flag("--dry-run", dry_run, "only validate the scene and print it resolved");
  if (const auto code = scene::parse_cli(app, argc, argv)) return *code;
  return scene::run_guarded("granular", [&]() -> int {
    const scene::Scene s = scene::load_scene(scene_path);
    if (dry_run) {
      if (rank == 0) print_dry_run(s);
      return 0;
    }
    if (out_dir.empty()) throw scene::InputError("granular run: --out DIR is required (unless --dry-run)");
    scene::refuse_out_overlap(out_dir, scene_path, "scene file");
    scene::install_interrupt_handler();
    granular::RunOptions opt;
    opt.np = np > 0 ? np : default_threads(ranks);
    // Results are built beside OUT and swapped in when the run completes
    // (see finish_run). Under mpirun every rank writes into rank 0's folder.
    long tag = static_cast<long>(::getpid());
#ifdef GRANULAR_HAVE_MPI
    if (ranks > 1) MPI_Bcast(&tag, 1, MPI_LONG, 0, MPI_COMM_WORLD);
#endif
    if (s.box && rank != 0) return 0;  // box runs are single-process
    std::optional<scene::StagedDir> staged;
    if (rank == 0) staged.emplace(out_dir, tag);
    opt.out_dir = scene::StagedDir::path_for(out_dir, tag);
    if (s.box) return finish_run(*staged, granular::run_box_scene(s, opt));
#ifdef GRANULAR_HAVE_MPI
    const granular::FlowResult r = granular::run_flow_scene(s, opt, mpi_group(mpi));
#else
    const granular::FlowResult r = granular::run_flow_scene(s, opt);
#endif
    if (rank != 0) return r.summary.value("interrupted", false) ? 1 : 0;
    return finish_run(*staged, r.summary);
  });
}
