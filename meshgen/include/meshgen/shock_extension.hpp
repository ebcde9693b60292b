#pragma once
// The predicted shock carried on to where the flow region ends. A shock does
// not stop inside the flow: an attached shock runs from the apex to the far
// field, a bow shock's wings run out through the outlet or the top. The
// predictor's accepted stations cover less (its fits are refused near the
// apex and near the domain's edges), so a band built only round them leaves
// the shock's ends in cells graded towards h_max, where a smeared jump costs
// the clustered grid the accuracy its band bought.
//
// Each end is extended straight along the curve's end tangent (the line
// fitted through the end stretch, the last quarter of the curve's length) to
// the first point where the line leaves the region (the body or the
// domain's boundary), but never farther than the end stretch is long: that
// far the data still say where the shock goes. Straight is exact for an
// attached shock (whose gaps are short: the extension reaches the edge); a
// bow shock's wing bends towards the Mach angle, and its extension may stop
// short of the edge.
//
// The half-width over the extension widens with the distance s from the end
// point as the extrapolation's uncertainty does:
//   w(s) = w_end + s (ci_a + ci_b) / L_stretch + kappa s (s + L_stretch) / 2
// the first term from the 95% position intervals at the two ends of the
// stretch (they bound the direction's 95% uncertainty), the second where the
// shock would be had it kept turning as it turns over the stretch (kappa:
// the turn between the stretch's halves over half its length; the fitted
// direction is the stretch's mean, half a stretch's turn behind the tip's
// tangent, hence s + L_stretch rather than s). A curve without stated
// intervals is extended all the same and keeps none: its band is meshgen's
// default width throughout.
#include <vector>

#include "meshgen/fluid_region.hpp"
#include "scene/vec2.hpp"

namespace meshgen {

struct ExtendedShock {
  std::vector<scene::Vec2> curve;
  std::vector<double> ci;     // empty when the input had none
  double start_length = 0.0;  // added before the first point, scene units
  double end_length = 0.0;    // added after the last point
};

// ci: one 95% half-width per point, or empty. Curves of fewer than two
// distinct points, and ends that already lie outside the region, are kept
// as they are.
ExtendedShock extend_shock_to_boundary(const std::vector<scene::Vec2>& curve,
                                       const std::vector<double>& ci, const FluidRegion& region);

}  // namespace meshgen
