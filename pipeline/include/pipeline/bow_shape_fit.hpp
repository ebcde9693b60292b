#pragma once
// A restitution per blunt shape: on each training body, the e at which the
// granular bow shock stands off as far as the gas's (shockfit's standoff,
// the fitted shock vertex's distance from the nose; the gas's from its own
// cells on the stagnation line), then e = c0 + c1/M^2
// fitted per shape class and judged by leaving each body out
// (docs/calibration.md, "A restitution per blunt shape").
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/bow_shock_scatter.hpp"
#include "pipeline/calibration.hpp"

namespace pipeline {

struct BowShapeOptions {
  std::string cache_dir;  // granular runs, by body and e (a rerun resumes)
  int np = 1;
  // The sweep around the wedge table's e(M) at the body's Mach number;
  // then `refinements` runs bisect the bracketing interval.
  std::vector<double> offsets{-0.015, -0.01, -0.005, 0.0, 0.005, 0.01};
  int refinements = 2;
  // Runs per e, at seeds that share no replica: one run's standoff scatters
  // by +-3-4% (95%), several times what 0.001 of e moves it on a disc.
  int seeds = 3;
};

// The gas's standoff of a training run, in body lengths: where the finest
// steady uniform grid's own cells put the density midpoint on the stagnation
// line when it stopped (cfd's shock probe, history.csv `shock_x`). Not
// shockfit's standoff on the grid's resampled lattice: the lattice's spacing
// (2% of a disc radius at 200 points) and the fitted vertex moved that by up
// to 6% from one uniform level to the next on the disc M4 case study, where
// the probe's readings on the two finest grids agree to 0.2%. InputError
// naming the file when there is no such reading.
double gas_standoff(const BowTrainingRun& run);

// e = c0 + c1/M^2 through the crossings, and each point's left-out e.
// nullopt with fewer than three points (two leave no left-out fit) or a
// singular design (every point at one Mach number).
std::optional<BowShapeFit> fit_bow_shape(const std::string& shape,
                                         const std::vector<BowShapePoint>& points);

// The pooled scatter's measure for a training run: its own granular stations
// against its gas shock when it ran at the wedge table's e(M); else (a run
// made at its shape's own e) the body rerun at the wedge e(M) (cached like
// the sweeps).
StationErrors wedge_station_errors(const BowTrainingRun& run, const CalibrationTable& t,
                                   const BowShapeOptions& o);

struct BowShapeResult {
  // Shapes with at least three bodies crossed whose left-out station RMS
  // beats the wedge e(M)'s on the same bodies (the others are reported only).
  std::vector<BowShapeFit> fits;
  nlohmann::json shapes = nlohmann::json::array();  // every shape fitted: its RMS, the baseline's
  double cpu_seconds = 0;                           // the granular runs this call made
  nlohmann::json report;                            // per body: sweep, crossing, left-out check
};
// Sweeps, fits and checks every shape the runs hold; a shape with fewer
// than three crossed bodies, or whose fit does not beat the wedge e(M) out
// of sample, gets none (said in the report).
// `wedge_errors[k]` is runs[k]'s wedge_station_errors (the baseline a
// shape's fit must beat), measured once by the caller for the pooled scatter.
BowShapeResult fit_bow_shapes(const std::vector<BowTrainingRun>& runs,
                              const std::vector<StationErrors>& wedge_errors,
                              const CalibrationTable& t, const BowShapeOptions& o);

}  // namespace pipeline
