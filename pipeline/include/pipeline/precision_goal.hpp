#pragma once
// Precision on demand for the granular predictor (docs/granular_flow.md,
// "Precision on demand"): the target the scene asks for, and the shock
// position's 95% half-width that shockfit gives the fields averaged so far.
#include <optional>

#include "granular/flow_run.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "shockfit/locate.hpp"

namespace pipeline {

// `target_half_width: mesh` asks for a shock position known to this many
// cells of the finest clustered grid. The clustered band is 3 h_min either
// side of the predicted shock (meshgen's default band_width) and a captured
// CFD shock is 2-4 cells thick, so its far side lies up to 2 h_min from its
// centre: a prediction off by at most 1 h_min keeps the whole captured shock
// inside the fine band.
inline constexpr double kTargetFineCells = 1.0;

// granular.target_half_width (body lengths), or for `mesh` kTargetFineCells
// x mesh.h_min x the finest of pipeline.levels; nullopt when the scene sets
// no target.
std::optional<double> precision_target(const scene::Scene& s);

// The 95% half-width of the shock position, in body lengths: an attached
// shock's angle half-width as the displacement it makes at the far end of
// the shock, l tan(ci), l the distance from the body's nose to the farthest
// accepted shock point (the shock pivots about the apex); a bow shock's
// standoff half-width. NaN when no shock was found.
double shock_position_half_width(const scene::Scene& s, const shockfit::ShockResult& r);

// `target_half_width: band`. An attached shock's band is the predicted angle
// +- hypot(the run's own 95% half-width, 1.96 x the calibration table's
// out-of-sample angle scatter) (band_angle_half_width_deg). Once the run's
// own half-width is below band_target_deg the band is at most kBandWidening
// wider than a perfectly averaged run's would be, and averaging on buys the
// grid almost nothing: the clustered grids' CFD speedup on wedge M3/10 did
// not change between 4 and 16 flow-through times (docs/case_studies.md).
// The goal also prices its averaging (PrecisionGoal::downstream_cpu, the
// cost model's finest clustered grid round the band): meshgen widens every
// band to at least 3 h_min either side, which on default sizes is wider than
// the angle's band over most of the shock, so averaging stops as soon as a
// chunk costs more CPU than the narrower band would save.
inline constexpr double kBandWidening = 0.2;
// No band stop before this many flow-through times: the shock angle still
// settles before (wedge M3/10: 23.8, 25.3, 26.2, 26.4 deg at 1-2.5), and from
// 4 to 16 the mean angle does not move (-0.02 deg, 95% -0.13 to +0.09, 16
// unseen wedges; docs/shockfit.md).
inline constexpr double kBandMinAveraging = 4.0;
// sqrt((1 + kBandWidening)^2 - 1) x the band's own half-width from the
// scatter alone (band_angle_half_width_deg with no run interval), deg.
double band_target_deg(double angle_scatter_deg);

// `target_half_width: standoff`: a bow shock averages until its standoff's
// 95% interval is at most this fraction of the standoff (two checks agreeing,
// the standoff moved by no more than that between them), or max_averaging.
// It is the standoff precision a bow-shock prediction is judged by; a fixed
// averaging gave +-1.4-5.2% on unseen discs at the table's e (docs/shockfit.md,
// "The standoff target").
inline constexpr double kStandoffTargetRelative = 0.03;

// The goal handed to the granular stage: inactive (fixed averaging) when the
// scene sets no target; else the target and a measure that runs shockfit.
// A band target needs the table's angle scatter (deg; InputError naming the
// key when NaN).
granular::PrecisionGoal precision_goal(const scene::Scene& s,
                                       double angle_scatter_deg = scene::kNaN);

// Where a scene leaves the averaging to the pipeline (no granular.averaging,
// no target) and the band of an attached gas shock is calibrated, a run that
// builds the band averages to `band`: sets target_from_band, true if it did.
// `pipeline predict` keeps the scene's averaging (the prediction is the
// product there, not a band).
bool default_to_band_target(scene::Scene& s, double angle_scatter_deg);

// Where a scene leaves the replicas open and its gas shock is detached, a run
// that builds the band with the table's bow-shock scatter (bow_relative, the
// relative distance error, RMS; NaN: none) averages kDefaultReplicas instead
// of kBowShockReplicas: that band is +-1.96 x bow_relative (about +-30%)
// wide, and the run's own +-3.6% adds nothing to it. True if it did.
bool default_to_band_replicas(scene::Scene& s, double bow_relative);

// Where a scene leaves the averaging open and its gas shock is detached,
// `pipeline predict` (whose product is the standoff, not a band) averages to
// `standoff`, no shorter than the scene's averaging: sets
// target_from_standoff, true if it did.
bool default_to_standoff_target(scene::Scene& s);

// Both of the above: what a run that builds the band averages, in one place
// for the run and its cost estimate.
void default_to_band_averaging(scene::Scene& s, double angle_scatter_deg, double bow_relative);

}  // namespace pipeline
