#pragma once
// Instantiating the case templates for a scene (private to cfd_core).
#include <map>
#include <string>

#include "cfd/foam_reader.hpp"
#include "scene/scene.hpp"

namespace cfd {

// Free-stream state of the normalised perfect gas (c = 1 at T = 1).
struct Freestream {
  double mach = 0, gamma = 1.4;
  double p = 1.0, T = 1.0;
  double rho() const { return gamma * p / T; }  // R = 1/gamma
};
Freestream freestream(const scene::Scene& s);

// Settings resolved from the scene and options.
struct CaseSettings {
  int np = 1;
  bool lts = false;
  double max_co = 0.0;  // Courant number the solver runs at (LTS: kLtsCourantFactor x cfd.max_co)
  double flow_through = 1.0;   // domain length / U
  double dt_ref = 0.0;         // global time step of the free stream at maxCo on this mesh
  double end_time = 0.0;       // body lengths / c
  double write_interval = 0.0; // body lengths / c
  long write_steps = 0;        // LTS: steps between written times
  double lts_smoothing = 0.0;  // LTS: rDeltaTSmoothingCoeff (controlDict)
};

// rhoCentralFoam's rDeltaTSmoothingCoeff under LTS: a cell's local step may
// exceed a neighbour's by this fraction at most. OpenFOAM's default, 0.02,
// lets the step grow only 2% per cell away from the smallest cell, so on a
// graded grid most of the domain marches near the smallest step, and the
// smoothing's own cost (a wave over the mesh each step) ate the rest of the
// gain: no CPU saved on the clustered M3/10 grid. At 1 (a step at most twice
// its neighbour's; meshgen grades cells by 1.2) LTS took 2.5-3.5x less CPU
// on the finest grids of both families with the same wall pressure to 0.1%
// (docs/bench_cfd.md); 0.2 was in between.
inline constexpr double kLtsSmoothingCoeff = 1.0;

// Under LTS each cell marches at its own Courant limit, and at cfd.max_co
// (0.3) the captured shock of a wedge never settled: the finest M5/20 grids
// of both families cycled with an L1 density error 20-30 % above the
// time-accurate steady state's for 6 iteration flow-throughs (clustered
// 0.0067-0.0072 against 0.0057, uniform 0.0127-0.0147 against 0.0111). At
// half of it they settle within 1-6 % of it (docs/bench_cfd.md, "The LTS
// limit cycle"), so LTS runs at this fraction of cfd.max_co.
inline constexpr double kLtsCourantFactor = 0.5;

// Whether the flow starts at rest (cfd.start, resolved for "auto": at rest
// where scene::starts_at_rest says so (not wedges), unless the free stream is below
// scene::rest_start_min_mach, where the start at rest sends a shock out
// through the inlet; then in the free stream).
bool start_at_rest(const scene::Scene& s);

// The initial state, cfd.start resolved: "rest", "freestream", or
// "rest_behind_base" (the free stream ahead of the body's widest station, gas
// at rest at free-stream pressure and temperature behind it). auto gives the
// last where a free-stream start meets a sharp base inside the domain (a
// wedge whose shock stands off), above the rest-start Mach limit (below it
// the shock between the free stream and the gas at rest runs out through
// the inlet, as from a start at rest): the base face moving away from the gas at
// Mach M opens an unsteady expansion whose wall pressure falls as
// (1 - (gamma - 1) M / 2)^(2 gamma / (gamma - 1)), 0.0016 of p at Mach 3 and a
// vacuum from Mach 5, and rhoCentralFoam died of a negative temperature there
// within ~30 steps at Mach 2.5-6 (docs/reliability.md), while a start at rest
// sends a bow shock far upstream that takes most of the run to come back.
std::string initial_state(const scene::Scene& s);

// The outlet's velocity condition. zeroGradient, except behind a sharp base
// inside the domain, where the wake's recirculation can reach the outlet
// (one base height behind the base): there zeroGradient let gas flow in
// without bound (the Mach 3, 36 deg wedge's clustered grid: backflow -0.3 to
// -3.9 c at the outlet, density 1e10 in the wake by 5.8 flow-throughs, the
// fallback too) and inletOutlet, which sets no inflow, settled in 6.
std::string outlet_velocity(const scene::Scene& s);

// 0/U's internalField for the initial state on `mesh`: uniform, or one
// velocity per cell for rest_behind_base.
std::string initial_velocity_field(const scene::Scene& s, const Mesh2D& mesh);

// Far-field outflow boundaries (outlet, top, bottom) when the estimated flow
// behind the shock at the outflow station is subsonic
// (scene::outflow_can_be_subsonic: Billig's shock, or a detached shock ahead
// of a sharp shoulder on the outflow boundary): the pressure is then one incoming
// characteristic, and extrapolating it (zeroGradient, right for supersonic
// outflow) leaves its level free: on the Mach 1.3 disc the bow shock drifted
// upstream without end. OpenFOAM's waveTransmissive lets outgoing waves
// leave and relaxes the pressure to the free stream's over a length
// kFarFieldRelaxationLength (docs/cfd_cases.md). Supersonic outflows keep
// zeroGradient.
bool subsonic_outflow(const scene::Scene& s);

// waveTransmissive's lInf, in body lengths. With 26 (the domain length) on
// the outlet alone the Mach 1.3 disc's bow shock still drifted upstream
// after 25 flow-throughs; with 1 on the outlet and the sides it settled (standoff ~7 R, Billig 6.1 R) and the density change
// fell below 5e-3 per flow-through (docs/reliability.md).
inline constexpr double kFarFieldRelaxationLength = 1.0;

// The pressure condition of the far-field boundaries as OpenFOAM entries.
std::string far_field_pressure(const scene::Scene& s);
// The reconstruction limiter (cfd.limiter, resolved for "auto").
std::string limiter(const scene::Scene& s);
// The flux scheme (cfd.flux_scheme, resolved for "auto").
std::string flux_scheme(const scene::Scene& s);
// Whether the case uses local time stepping (cfd.local_time_stepping,
// resolved for "auto").
bool local_time_stepping(const scene::Scene& s);

// Replaces every @KEY@ in `text`; std::logic_error for a placeholder left over.
std::string fill_placeholders(const std::string& text, const std::map<std::string, std::string>& values,
                              const std::string& origin);

// Largest stable global time step of the free stream on `m` at Courant
// number max_co, using rhoCentralFoam's definition
// Co = 0.5 dt sum_faces (|U.Sf| + c |Sf|) / V.
double free_stream_time_step(const Mesh2D& m, const Freestream& f, double max_co);

// Iterations a signal needs to cross the domain (length `width`) at the
// free-stream speed when every cell takes its own free-stream step at
// max_co (local time stepping without smoothing): width times the
// area-weighted mean of 1 / (U dt_cell). On a uniform grid this is the
// time-accurate steps per flow-through; on a clustered one, far fewer.
long lts_steps_per_flow_through(const Mesh2D& m, const Freestream& f, double max_co, double width);

// Checks the mesh patches against the roles the templates know.
void check_patches(const Mesh2D& m, const std::string& mesh_dir);

// Creates case_dir from the templates, the mesh and the settings; copies
// 0.orig to 0. Replaces an existing case there (InputError if case_dir holds
// something that is not an OpenFOAM case).
void write_case(const scene::Scene& s, const std::string& mesh_dir, const Mesh2D& mesh,
                const std::string& case_dir, const CaseSettings& cs);

// Sets `key value;` in system/controlDict (atomic, so the running solver
// never reads half a file).
void set_control(const std::string& case_dir, const std::string& key, const std::string& value);

}  // namespace cfd
