#pragma once
// Shock predictors behind one interface, chosen by name: each places the
// shock a clustered grid is built around, with a per-point 95% half-width
// and its CPU cost. meshgen takes only the curve and its interval
// (shock.csv), whatever produced it.
//   granular    the granular gas and shockfit's two-line fits (the project's method)
//   correlation theta-beta-Mach for attached wedges (exact), Billig's
//               cylinder shock for other bodies (an empirical approximation)
//   coarse_cfd  a coarse uniform CFD run to steady state, located by shockfit
//   adapt       the same coarse run, and a size field per level from the
//               Hessian of its density: grids adapted as a CFD engineer
//               would, instead of a band round a curve
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"
#include "scene/shock_kind.hpp"
#include "scene/units.hpp"
#include "scene/vec2.hpp"

namespace pipeline {

struct BowStationBias;

struct Prediction {
  std::string predictor;
  scene::ShockKind kind = scene::ShockKind::none;
  std::vector<scene::Vec2> curve;  // accepted shock points in order (scene coordinates)
  std::vector<double> half_width;  // 95% half-width along the shock normal per point (body lengths)
  double shock_angle_deg = scene::kNaN;
  double shock_angle_ci_deg = scene::kNaN;
  double standoff = scene::kNaN;  // body lengths
  double standoff_ci = scene::kNaN;
  double cpu_seconds = 0, wall_seconds = 0;
  std::string shock_csv;  // the curve as written for meshgen
  // Predictors that size grids themselves (adapt): per family level, a
  // size field .vti (field "h", body lengths) meshed instead of the band
  // round the curve.
  std::vector<std::pair<double, std::string>> size_fields;
  std::string fingerprint;                            // changes whenever the prediction would
  nlohmann::json details = nlohmann::json::object();  // predictor-specific figures
  // `predictor`, `shock`, angle or standoff with its interval, `cpu_seconds`,
  // `size_fields` (level and path; empty for band predictors), details.
  nlohmann::json summary() const;
};

struct PredictContext {
  const scene::Scene& scene;
  std::string out_dir;  // the predictor's own directory (cached stages live below it)
  // The pipeline run's directory: CFD grids shared with the families live there.
  std::string run_dir;
  int np = 1;
  bool force = false;  // recompute cached stages
  // The calibration table's out-of-sample scatter of the granular shock
  // angle (deg, RMS), when the scene's restitution came from the table and
  // the body has a wedge angle; NaN otherwise. Widens an attached shock's band.
  double calibration_angle_scatter_deg = scene::kNaN;
  // The table's out-of-sample relative error of a bow shock's distances
  // (RMS), when the restitution came from it and the body has no wedge
  // angle; NaN otherwise. Widens a detached shock's band.
  double calibration_bow_shock_relative_rms = scene::kNaN;
  // The table's station bias for the body's shape (calibration.hpp): a
  // detached shock's stations and standoff are corrected by it. nullptr: none.
  const BowStationBias* bow_station_bias = nullptr;
};

class Predictor {
 public:
  virtual ~Predictor() = default;
  virtual std::string name() const = 0;
  virtual Prediction predict(const PredictContext& cx) const = 0;
};

std::vector<std::string> predictor_names();
// InputError naming the predictors there are for an unknown name.
std::unique_ptr<Predictor> make_predictor(const std::string& name);

// shock.csv through scene/shock_csv.hpp (the one format meshgen reads) for
// predictors that do not run shockfit: every point accepted, its half-width
// in the ci column.
void write_shock_curve(const std::string& path, const std::vector<scene::Vec2>& curve,
                       const std::vector<double>& half_width);

// An attached shock as meshgen should see it: the ray from the body's nose
// (the apex, where the inviscid shock starts) at `angle_deg` to where it
// leaves the domain, kPoints + 1 points, each with the 95% half-width the
// angle's interval gives at its distance from the apex,
// s tan(angle_ci_deg) (0 for an exact angle: meshgen's smallest band).
struct ShockCurve {
  std::vector<scene::Vec2> points;
  std::vector<double> half_width;
};
ShockCurve apex_ray(const scene::Domain& d, scene::Vec2 apex, double angle_deg,
                    double angle_ci_deg);

// A bow shock as a correlation places it ahead of the scene's body: Billig's
// cylinder shock with the body's correlation nose radius
// (scene::correlation_nose_radius), its vertex billig_standoff(s) (scene
// units) ahead of the nose, clipped to the scene's domain (the lower branch
// too when the domain is not symmetric), every point with the 95% half-width
// relative_half_width x that standoff.
double billig_standoff(const scene::Scene& s);
ShockCurve billig_bow_shock(const scene::Scene& s, double relative_half_width);

// The 95% half-width of the angle an attached shock's band covers: the
// measured angle's own interval combined in quadrature with the calibration's
// out-of-sample scatter (kZ95 times its RMS), which the run's interval cannot
// see: the restitution itself is a fit. A NaN scatter adds nothing.
double band_angle_half_width_deg(double angle_ci_deg, double calibration_scatter_deg);
// The half-width of a bow shock's band at a station whose shock lies
// `distance` from the body with its own 95% half-width ci: the interval
// combined with the calibration's relative scatter at the same 95% level,
// hypot(ci, 1.96 relative_rms distance). ci alone when the scatter is NaN.
double band_bow_half_width(double ci, double distance, double relative_rms);

struct ShockPoint {
  scene::Vec2 point;
  double half_width = 0;
  double distance = scene::kNaN;  // from the body along the station's normal (NaN: not stated)
};
// The accepted points of a shock.csv in file order (InputError naming the
// file when it is malformed or holds fewer than two).
std::vector<ShockPoint> read_accepted_shock(const std::string& path);

}  // namespace pipeline
