#pragma once
// Speed against error: the clustered and uniform families of CFD runs, the
// reference for the body, and the speedup at equal error.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/units.hpp"

namespace pipeline {

struct GridRun {
  std::string family;        // clustered | uniform
  double level = 1;          // h = level x h_min
  long cells = 0;
  double mesh_seconds = 0;
  double cfd_wall_seconds = 0;
  long steps = 0;
  bool steady = false;
  std::string shock;         // attached | detached | none
  double value = 0;          // shock angle (deg) or standoff (body lengths)
  double value_ci = 0;
  double error = 0;          // |value - reference| (deg) or relative standoff error
  double wall_pressure_ratio = 0;
  double pressure_error = 0; // relative, wedges only (NaN otherwise)
  double speedup_cfd = 0;    // clustered: uniform time at this run's error / this run's time
  // Costs in CPU seconds (user + system, children included): the meshing
  // stage (gmsh, the grid files, checkMesh) and the solver (all ranks).
  double mesh_cpu_seconds = scene::kNaN;
  double cfd_cpu_seconds = scene::kNaN;
  double flow_throughs = scene::kNaN;
  // Exact-reference error measures (error_measures.hpp); NaN where they do not apply.
  double primary_error = scene::kNaN;
  double primary_error_ci = scene::kNaN;
  double l1_density = scene::kNaN;
  double l1_density_ci = scene::kNaN;
  double l1_pressure = scene::kNaN;
  double stagnation_pressure_ratio = scene::kNaN;
  double stagnation_pressure_error = scene::kNaN;
  double stagnation_pressure_error_ci = scene::kNaN;
  double l1_total_enthalpy = scene::kNaN;
  double shock_axis_deviation_cells = scene::kNaN;  // carbuncle check
  double drag_coefficient = scene::kNaN;
  std::string note;          // what went wrong measuring this run, if anything
  // The flux and limiter its result carries ("Kurganov/vanLeer"); empty
  // without a CFD run.
  std::string scheme;
  // Its case under cfd/ and its mesh under meshgen/: the grid's name, with
  // suffixes where it was meshed or solved again otherwise (grid_runs.hpp:
  // GridVariant).
  std::string case_name, mesh_name;
  bool strips = false;     // its band holds shock-aligned strips (meshgen's band_strips > 0)
  bool fell_back = false;  // its first attempt diverged (cfd.fallback)
  double cpu_us_per_cell_step() const;
  nlohmann::json to_json() const;
};

struct Reference {
  std::string quantity;      // shock_angle_deg | standoff
  std::string source;        // theta-beta-Mach | Billig | finest uniform grid
  double value = 0;
  double pressure_ratio = 0; // wedges: oblique-shock p2/p1 (NaN otherwise)
};

struct Comparison {
  std::vector<GridRun> clustered, uniform;  // coarse to fine
  // Clustered headline run (the finest) and its uniform match: the coarsest
  // uniform grid at least as accurate, else the finest uniform grid.
  int clustered_pick = -1, uniform_pick = -1;
  bool uniform_matches = false;
  // CFD wall time of the uniform family interpolated (log-log) at the
  // clustered pick's error, over the clustered pick's time. NaN when the
  // uniform family never reaches that error (then `speedup_bound` holds the
  // lower bound finest-uniform time / clustered time).
  double speedup_cfd = 0, speedup_total = 0, speedup_bound = 0, speedup_total_bound = 0;
};

// Error measure of one run against the reference.
void score(GridRun& r, const Reference& ref);
Comparison compare(std::vector<GridRun> clustered, std::vector<GridRun> uniform,
                   double granular_seconds);

}  // namespace pipeline
