#include "pipeline/calibration_training.hpp"

#include <cmath>
#include <sstream>

#include "scene/body_traits.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kDeg;
// Two wedges are the same case when Mach and angle agree to this (the
// values are written by hand to at most a few decimals).
constexpr double kSameWedgeTolerance = 1e-9;
// Flow-through times a generated training wedge averages by default: the
// table was fitted at 4 up to Mach 8, where the mean angle hardly moves with
// the averaging (16 against 4: -0.02 deg, 95% -0.13 to +0.09; docs/shockfit.md
// "Sixteen flow-through times"), so the sweeps keep 4 (a third of the CPU)
// and reproduce those crossings. At Mach 9-10 a fit of 12 reads 0.135 deg
// above one of 4, yet crossings swept there at 12 lost out of sample (they
// sit on a step of angle(e); docs/calibration.md "The averaging the
// crossings are read at"): `--averaging` is there to sweep at another.
constexpr double kTrainingAveraging = 4.0;
}  // namespace

bool same_wedge(const WedgePoint& a, const WedgePoint& b) {
  return std::abs(a.mach - b.mach) < kSameWedgeTolerance &&
         std::abs(a.angle_deg - b.angle_deg) < kSameWedgeTolerance;
}

std::vector<WedgePoint> training_wedges(const std::vector<double>& machs,
                                        const std::vector<double>& angles_deg, double gamma,
                                        const std::vector<WedgePoint>& excluded) {
  std::vector<WedgePoint> out;
  for (const double m : machs)
    for (const double a : angles_deg) {
      const WedgePoint p{m, a};
      if (!scene::oblique_shock_beta(m, a * kDeg, gamma)) continue;  // detached: no angle to match
      bool clash = false;
      for (const auto& x : excluded) clash = clash || same_wedge(p, x);
      if (!clash) out.push_back(p);
    }
  return out;
}

std::vector<WedgePoint> wedge_points(const std::vector<std::string>& scene_paths) {
  std::vector<WedgePoint> out;
  for (const auto& path : scene_paths) {
    const scene::Scene s = scene::load_scene(path);
    if (const auto angle_deg = s.body ? scene::calibration_angle_deg(*s.body) : std::nullopt)
      out.push_back({s.freestream.mach, *angle_deg});
  }
  return out;
}

double default_training_averaging() {
  return kTrainingAveraging;
}

scene::Scene training_scene(const WedgePoint& p, double averaging_flow_throughs) {
  std::ostringstream name, yaml;
  name << "train_M" << p.mach << "_" << p.angle_deg;
  yaml << "name: " << name.str() << "\n"
       << "body: {kind: wedge, angle_deg: " << p.angle_deg << ", length: 1.0}\n"
       << "freestream: {mach: " << p.mach << ", gamma: 1.4}\n"
       << "granular: {averaging: " << averaging_flow_throughs << "}\n";
  return scene::parse_scene(yaml.str(), "calibrate training wedge " + name.str());
}

}  // namespace pipeline
