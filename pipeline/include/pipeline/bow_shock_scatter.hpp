#pragma once
// The granular bow shock against the gas's, station by station: how far
// the prediction's shock distances miss on blunt bodies it was not fitted
// on. The calibration's e(M) is fitted on wedge angles only; this measures
// what it gives a bow shock, so a clustered grid's band can cover it as an
// attached shock's band covers the table's angle scatter.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pipeline/calibration.hpp"
#include "scene/scene.hpp"

namespace pipeline {

struct StationErrors {
  std::string body;              // the scene's name
  double mach = scene::kNaN;     // its free-stream Mach number
  std::vector<double> relative;  // (d_granular - d_gas) / d_gas per station both accepted
  // The same stations' body-normal inclinations (deg; bow_station_bias.hpp);
  // NaN where the granular file has no normal columns.
  std::vector<double> inclination_deg;
  std::string shape;  // scene::bow_shape_class of the body ("" for none)
  // The granular standoff's relative error against the gas's
  // stagnation-line standoff (gas_standoff); NaN where not measured.
  double standoff_relative = scene::kNaN;
  double rms = scene::kNaN;      // of `relative`
  double mean = scene::kNaN;
  double cpu_seconds = scene::kNaN;  // the run's predictor and the compared uniform grid
};

// `rms` and `mean` of e.relative (which must not be empty).
void set_mean_and_rms(StationErrors& e);

// Stations are matched by index; both files must come from the same body's
// station layout (surface points equal to kSameStation), else InputError.
// Fewer than kMinStations common stations: InputError naming the files.
StationErrors station_errors(const std::string& granular_csv, const std::string& gas_csv);

// A blunt training body: a finished `pipeline run` of it with the granular
// predictor, checked as below, and the gas shock it is compared with (the
// finest steady uniform grid's shockfit stations, and its case directory,
// whose history.csv holds its own stagnation-line shock).
struct BowTrainingRun {
  scene::Scene scene;
  std::string run_dir;
  std::string gas_csv, gas_case;
  double predictor_cpu_seconds = scene::kNaN, grid_cpu_seconds = scene::kNaN;
};
BowTrainingRun bow_training_run(const std::string& run_dir);
// Whether a run's resolved scene took the table's wedge e(M) (as applied,
// rounded to kRestitutionQuantum): the e the pooled scatter belongs to.
bool ran_at_table_restitution(const scene::Scene& ran, const CalibrationTable& t);

// A finished `pipeline run` of a blunt body with the granular predictor:
// RUNDIR/shockfit/shock.csv against the finest steady uniform grid's
// RUNDIR/cfd/uniform_h<level>/shockfit/shock.csv. InputError (naming the
// directory) for a wedge, another predictor, no steady uniform grid, or a
// case study's body at its Mach number (the case studies are predictions).
StationErrors run_station_errors(const std::string& run_dir);

// The granular standoff (shockfit's, in the summary at granular_summary)
// against the run's gas stagnation-line standoff (gas_standoff), relative.
double standoff_relative_error(const std::string& granular_summary, const BowTrainingRun& r);

// Each body's RMS counts once.
BowShockScatter pooled_scatter(const std::vector<StationErrors>& bodies);

// `pipeline calibrate --bow-shock-runs RUNDIR...`: measures the scatter on
// the runs and writes it into the table at table_path (default: the
// built-in one), keeping everything else; runs nothing. Returns the figures.
// With `shapes`, it also fits each blunt shape's own e(M) on the runs' bodies
// (granular runs, cached under shapes->cache_dir; bow_shape_fit.hpp).
struct BowShapeOptions;
nlohmann::json calibrate_bow_shocks(const std::vector<std::string>& run_dirs,
                                    const std::string& table_path,
                                    const BowShapeOptions* shapes = nullptr);

// `pipeline calibrate --bow-shock-runs RUNDIR... --station-bias`: fits each
// shape's station bias (bow_station_bias.hpp) on the runs (every one at the
// table's blunt law) and writes it into the table's bow block, leaving its
// pooled scatter, shape fits and other shapes' biases as they are; a shape
// whose fit does not beat its uncorrected stations out of sample gets none
// (said in the returned report). InputError without a bow block recording
// its law.
nlohmann::json calibrate_station_biases(const std::vector<std::string>& run_dirs,
                                        const std::string& table_path);

}  // namespace pipeline
