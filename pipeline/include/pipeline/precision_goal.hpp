#pragma once
// Precision on demand for the granular predictor (docs/granular_flow.md,
// "Precision on demand"): the target the scene asks for, and the shock
// position's 95% half-width that shockfit gives the fields averaged so far.
#include <optional>

#include "granular/flow_run.hpp"
#include "scene/scene.hpp"
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

// The goal handed to the granular stage: inactive (fixed averaging) when the
// scene sets no target; else the target and a measure that runs shockfit.
granular::PrecisionGoal precision_goal(const scene::Scene& s);

}  // namespace pipeline
