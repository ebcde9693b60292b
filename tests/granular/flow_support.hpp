#pragma once
// Helpers shared by the flow tests: small scenes, free-stream statistics and
// a simple shock-angle fit on the volume-fraction field.
#include <optional>
#include <string>

#include "scene/lattice.hpp"

namespace flowtest {

// Mean of `field` over cells with x < x_max (upstream of the body), outside it.
double upstream_mean(const scene::Lattice& lat, const std::string& field, double x_max);
// Largest finite value of `field`.
double max_of(const scene::Lattice& lat, const std::string& field);

struct ShockFit {
  double angle_deg = 0;      // from +x, of the line fitted through the front
  double angle_se_deg = 0;   // standard error of the slope, in degrees
  int points = 0;
};
// Oblique shock from a wedge apex at the origin: in each column with
// x in [x_lo, x_hi] the front is the highest cell (scanning down from the
// top) whose volume fraction exceeds `threshold`; a line through those
// points (least squares) gives the angle.
std::optional<ShockFit> fit_wedge_shock(const scene::Lattice& lat, double threshold, double x_lo, double x_hi);

std::string temp_dir(const std::string& name);

}  // namespace flowtest
