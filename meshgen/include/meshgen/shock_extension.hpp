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
// fitted through the end stretch, kEndStretch of the curve's length) to the
// first point where the line leaves the region (the body or the domain's
// boundary). Straight is exact for an attached shock; a bow shock's wings
// straighten towards the Mach angle, so the tangent errs by the curvature
// left over the extension, which the widening half-width below covers.
//
// The half-width over the extension widens with the distance s from the end
// point as the extrapolated line's position uncertainty does:
//   w(s) = w_end + s (ci_a + ci_b) / L_stretch
// (the 95% position intervals at the two ends of the stretch over its length
// bound the direction's 95% uncertainty). Without stated intervals it stays
// w_end (0 here: the band's default width applies).
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
ExtendedShock extend_shock_to_boundary(const std::vector<scene::Vec2>& curve, const std::vector<double>& ci,
                                       const FluidRegion& region);

}  // namespace meshgen
