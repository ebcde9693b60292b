#pragma once
// The verdict of `pipeline run`: does the grid clustered at the predicted
// shock reach the uniform family's accuracy in less CPU time? Each family's
// primary error is fitted against CPU cost (log-log, equal_error.hpp) and
// the cost ratio read at the clustered family's finest error (or, when that
// lies below every uniform grid's, at the finest error both families reach),
// with a 95% interval; "faster"/"slower" only when the interval excludes 1.
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/equal_error.hpp"
#include "pipeline/work_price.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace pipeline {

// The error that drives the verdict for a scene, and why.
struct PrimaryError {
  std::string name;       // l1_density | l1_total_enthalpy
  std::string reference;  // how the reference value is obtained
  std::string why;        // one sentence for the report
};
PrimaryError primary_error_for(const scene::Scene& s);

// One grid's costs and primary error, as the verdict needs them.
struct VerdictRun {
  std::string family;     // clustered | uniform
  double level = 1;
  long cells = 0;
  long steps = 0;         // solver time steps to steady state
  double cfd_cpu = 0;     // solver CPU seconds (all ranks)
  double mesh_cpu = 0;    // meshgen's CPU seconds: gmsh, grid files, checkMesh
  double error = 0;       // primary error
  double error_ci = 0;    // its 95% half-width
  bool steady = false;
  std::string case_name;  // its case under cfd/ (empty: the grid's name)
};

struct FamilyFitInfo {
  // Error against CFD CPU, and against the grid's meshing + CFD CPU (the
  // family's predictor, paid once, is added to the cost read off the fit).
  LogLogFit cfd, total;
  int used = 0;           // runs in the fit
  std::vector<std::string> excluded;  // "uniform_h4: not steady", ...
};

struct Verdict {
  PrimaryError primary;
  // The clustered family's finest usable error; when it lies below every
  // uniform grid's and the clustered family reaches the uniform finest's
  // error, that error instead, so both fits are read inside their range.
  double target_error = 0;
  bool extrapolated = false;    // target outside the uniform family's error range
  // With the target moved: the speedups at the clustered finest error itself,
  // extrapolating the uniform fit past its finest grid (a secondary figure).
  struct BeyondUniform {
    double error = scene::kNaN;
    Interval speedup_cfd{scene::kNaN, scene::kNaN, scene::kNaN};
    Interval speedup_total{scene::kNaN, scene::kNaN, scene::kNaN};
  } beyond_uniform;
  Interval speedup_cfd, speedup_total;
  std::string verdict = "not distinguishable";      // on total CPU (predictor and meshing counted)
  std::string verdict_cfd = "not distinguishable";  // on CFD CPU alone
  double predictor_cpu = 0;
  // Costs are priced by the work model fitted on this run's timings
  // (work_price.hpp) when `priced`; otherwise the measured CPU seconds.
  bool priced = false;
  WorkPrice price;
  Interval measured_cfd, measured_total;  // the same ratios on the measured single timings
  FamilyFitInfo clustered, uniform;
  // The restitution calibration, made once and shared by every scene it
  // serves, as a separate line: its CPU, its share over the scenes it serves,
  // and the total speedup if this scene alone paid for it. NaN/empty when
  // the scene's predictor used no calibration table.
  struct Calibration {
    double cpu_seconds = scene::kNaN;
    int scenes_served = 0;
    Interval speedup_total_if_alone{};
    std::string verdict_if_alone;
  } calibration;
  std::string note;             // why no verdict could be given, when none
};

// A run's CFD and meshing CPU seconds as the verdict counts them.
double verdict_cfd_cpu(const Verdict& v, long cells, long steps, double measured);
double verdict_mesh_cpu(const Verdict& v, long cells, long steps, double measured);

// `uniform_predictor_cpu`: what the slow family's own predictor cost (0 for
// uniform grids; a second predictor's family in a head-to-head comparison).
Verdict make_verdict(const PrimaryError& primary, const std::vector<VerdictRun>& clustered,
                     const std::vector<VerdictRun>& uniform, double predictor_cpu, double uniform_predictor_cpu = 0);

// Fills v.calibration: the same comparison with the calibration's whole CPU
// added to the predictor's.
void charge_calibration(Verdict& v, const std::vector<VerdictRun>& clustered, const std::vector<VerdictRun>& uniform,
                        double calibration_cpu, int scenes_served);

nlohmann::json interval_json(const Interval& i);
nlohmann::json verdict_json(const Verdict& v);

}  // namespace pipeline
