#pragma once
// The training wedges of `pipeline calibrate`: generated scenes on a
// (Mach, deflection) grid, disjoint from the wedge case studies so that the
// case studies' restitution is an out-of-sample prediction.
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace pipeline {

struct WedgePoint {
  double mach = 0, angle_deg = 0;
};

// Grid points attached at `gamma` that are not within a rounding tolerance
// of any `excluded` point, Mach-major in the order given.
std::vector<WedgePoint> training_wedges(const std::vector<double>& machs,
                                        const std::vector<double>& angles_deg, double gamma,
                                        const std::vector<WedgePoint>& excluded);

// (Mach, angle) of the wedge scenes among `scene_paths` (other bodies skipped).
std::vector<WedgePoint> wedge_points(const std::vector<std::string>& scene_paths);

// Flow-through times a generated training wedge averages by default
// (calibration_training.cpp says why 4).
double default_training_averaging();

// A wedge scene at (mach, angle_deg) with every other key at its default,
// as the case-study scenes have them (wedge length 1, gamma 1.4, default
// granular settings), except the averaging: `averaging_flow_throughs`;
// named train_M<mach>_<angle>.
scene::Scene training_scene(const WedgePoint& p,
                            double averaging_flow_throughs = default_training_averaging());

bool same_wedge(const WedgePoint& a, const WedgePoint& b);

}  // namespace pipeline
