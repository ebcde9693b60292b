#pragma once
// OpenFOAM rhoCentralFoam cases for a scene: instantiate the templates in
// cfd_cases/templates (OpenFOAM's layout: 0.orig/, constant/, system/,
// Allrun), run the solver with a steady-state monitor, resample the result.
// Units: lengths in body lengths, speeds in free-stream speeds of sound,
// p = T = 1 and rho = gamma in the free stream (docs/cfd_cases.md).
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/errors.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"

namespace cfd {

struct CaseOptions {
  int np = 1;                                 // overrides scene cfd.np when > 1
  std::optional<bool> local_time_stepping;    // overrides scene cfd.local_time_stepping
  std::optional<double> lts_smoothing;        // LTS rDeltaTSmoothingCoeff (default: case_setup.hpp)
  // A written time directory (named for its time) of a case on the same
  // mesh: the run continues from that state instead of the initial one.
  std::string continue_from;
};

struct CaseResult {
  bool steady_state_reached = false;
  double wall_seconds = 0.0;   // solver start to solver exit (steady stop included)
  // User + system CPU of rhoCentralFoam (all ranks) and of decomposePar and
  // reconstructPar when parallel: the load-independent cost of the run.
  double cpu_seconds = 0.0;
  double sim_time = 0.0;       // simulated (pseudo-)time of the final state, body lengths / c
  long steps = 0;              // solver time steps
  long cells = 0;
  double wall_pressure_ratio = 0.0;  // wedge: mean wall p / free-stream p on the face; NaN otherwise
  std::string case_dir;
  std::string history_csv;
  // Extra facts for reports.
  double flow_through_time = 0.0;    // domain length / free-stream speed
  double final_density_change_l2 = 0.0;   // per flow-through time, relative to rho_inf
  double final_density_change_max = 0.0;
  double final_force_change = 0.0;
  bool local_time_stepping = false;
  int np = 1;
  std::string start;    // "rest" or "freestream" (cfd.start, resolved)
  std::string outflow;  // "supersonic" (zeroGradient far field) or "subsonic" (waveTransmissive)
  std::string flux_scheme;  // cfd.flux_scheme, resolved ("Kurganov" or "Tadmor")
  std::string limiter;      // cfd.limiter, resolved ("vanLeer" or "Minmod")
  // Empty, or the robust settings the run restarted with after the first
  // attempt diverged, and why (its CPU, wall seconds and steps are included above).
  std::string fallback;
  nlohmann::json summary() const;
};

// The solver diverged (floating-point exception, negative temperature, NaN
// fields): what it had spent, for a restart to add to.
class Diverged : public scene::RunError {
 public:
  Diverged(const std::string& what, double cpu, double wall, long solver_steps,
           double flow_through_time)
      : scene::RunError(what),
        cpu_seconds(cpu),
        wall_seconds(wall),
        steps(solver_steps),
        time_per_flow_through(flow_through_time) {}
  double cpu_seconds, wall_seconds;
  long steps;
  // One flow-through in the solver's (pseudo-)time: where a restart from a
  // written state stands in flow-throughs.
  double time_per_flow_through;
};

// Runs the scene on the mesh in mesh_dir/constant/polyMesh (patches inlet,
// outlet, top, bottom, body, frontAndBack) in case_dir (created; an existing
// case there is replaced). Throws scene::RunError on divergence or a solver
// failure (the case is kept for inspection), scene::InputError on a bad mesh.
CaseResult run_case(const scene::Scene& s, const std::string& mesh_dir, const std::string& case_dir,
                    const CaseOptions& o);

// How long the restart after a divergence runs with the robust settings
// before it returns to the scene's own. On the disc M4 case study's
// clustered finest grid, Kurganov diverged in the start-up transient at 5
// flow-throughs, again at half the Courant number from the state before
// it, and not once Tadmor had carried that state one flow-through on.
inline constexpr double kBridgeFlowThroughs = 1.0;

// run_case, and when it diverges and the scene's cfd.fallback allows, a
// restart. First a bridge: from the state written a write interval before
// the last one the divergence left, kBridgeFlowThroughs with the robust
// settings (robust_settings: Tadmor flux, Minmod limiter, half the Courant
// number), then on to the steady state with the scene's own settings, so
// the result carries the scene's scheme and its accuracy. Where fewer than
// two states were written or the bridge diverges too, from the initial
// state with the robust settings throughout. The result records the
// fallback and counts every attempt's CPU and wall seconds and steps; the
// diverged attempt's log and history stay in the case as
// log.rhoCentralFoam.diverged and history.diverged.csv (the bridge's as
// .bridge, a restart that diverged as .restart-diverged).
CaseResult run_case_with_fallback(const scene::Scene& s, const std::string& mesh_dir, const std::string& case_dir,
                                  const CaseOptions& o);
// The scene's cfd settings made robust; `what` describes the change.
scene::CfdParams robust_settings(const scene::CfdParams& p, std::string& what);

// Resamples the latest time of case_dir onto an nx x ny lattice covering the
// scene domain: fields rho, u, v, p, T, mach and inside_body (1 inside, 0
// outside; the others NaN inside the body or outside the mesh). Writes nothing.
scene::Lattice resample_to_lattice(const scene::Scene& s, const std::string& case_dir, int nx, int ny);

// Development/test grid without meshgen: a uniform blockMesh grid of the upper
// half of a wedge scene (symmetry plane, then the wedge face as `body`), with
// about `cells` cells; writes out_dir/constant/polyMesh (and log.blockMesh).
// InputError for a scene that is not an attached-shock wedge.
void make_wedge_block_mesh(const scene::Scene& s, long cells, const std::string& out_dir,
                           double grading_y = 1.0);

// Directory of the case templates: $SHOCKGRAIN_CFD_TEMPLATES, the source tree
// (compile-time), or <exe>/../share/shockgrain/cfd_cases/templates.
std::string template_dir();

}  // namespace cfd
