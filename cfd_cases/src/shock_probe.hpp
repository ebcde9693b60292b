#pragma once
// Where a bow shock stands on the stagnation line, measured on a written time:
// the steady-state rule's view of a shock that drifts while the body force
// barely moves (docs/cfd_cases.md, "Steady state").
#include <cstddef>
#include <optional>
#include <vector>

#include "cfd/foam_reader.hpp"
#include "scene/scene.hpp"

namespace cfd {

// A shock position on the stagnation line and the spacing of the cells it
// was interpolated between (scene units); NaN when not measured.
struct ShockReading {
  double x;
  double cell;
};

class ShockProbe {
 public:
  // The probe of a scene whose shock may stand off its body
  // (scene::shock_may_stand_off); nullopt for attached shocks, which are
  // judged without it. `parts`: the case's meshes, in the order their
  // cells are concatenated in a Snapshot.
  static std::optional<ShockProbe> for_scene(const scene::Scene& s,
                                             const std::vector<Mesh2D>& parts);

  // The most upstream point on the stagnation line, ahead of the nose, where
  // the density rises through the midpoint between the free-stream and the
  // normal-shock density, linearly interpolated between the cells the line
  // crosses; NaN where the line holds no such rise (no shock ahead of the
  // nose). `rho`: the cell densities of all parts, concatenated.
  ShockReading measure(const std::vector<double>& rho) const;

  double threshold() const { return rho_mid_; }
  std::size_t samples() const { return samples_.size(); }

 private:
  // A cell cut by the line: the midpoint of its chord and its index in the
  // concatenated fields.
  struct Sample {
    double x;
    std::size_t cell;
  };
  ShockProbe(std::vector<Sample> samples, double rho_mid)
      : samples_(std::move(samples)), rho_mid_(rho_mid) {}

  std::vector<Sample> samples_;  // upstream first
  double rho_mid_;
};

}  // namespace cfd
