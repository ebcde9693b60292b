#pragma once
// Reading the written times of a running case (serial, or every processorN
// of a decomposed one) and the steady-state measures between them.
#include <optional>
#include <string>
#include <vector>

#include "case_setup.hpp"
#include "cfd/foam_reader.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "shock_probe.hpp"

namespace cfd {

struct Snapshot {
  double time = 0.0;
  std::string name;
  std::vector<double> rho;  // all parts, concatenated
  scene::Vec2 force;        // pressure force on the forebody (upstream-facing faces) per unit depth
  double wall_pressure_ratio = 0.0;  // NaN unless a wedge
  // The bow shock on the stagnation line; NaN unless measured (ShockProbe).
  ShockReading shock{scene::kNaN, scene::kNaN};
};

struct HistoryRow {
  double time = 0, flow_throughs = 0, wall_seconds = 0;
  long steps = 0;
  double drho_l2 = 0, drho_max = 0, dforce = 0;  // per flow-through time
  scene::Vec2 force;
  double wall_pressure_ratio = 0;
  // Bow shock on the stagnation line (ShockProbe; NaN where not measured):
  // its x, the spacing of the cells it lies between, its change since the
  // row before per flow-through, and its drift, the least-squares slope per
  // flow-through over the steady rule's window (set by SteadyState::add).
  double shock_x = scene::kNaN, shock_cell = scene::kNaN, dshock = scene::kNaN,
         shock_drift = scene::kNaN;
};

// A written time holds a non-finite or non-positive density or pressure:
// the solution diverged.
class NonPhysicalState : public scene::RunError {
 public:
  using scene::RunError::RunError;
};

class CaseReader {
 public:
  // np > 1: reads processor0..np-1 (the decomposed case).
  CaseReader(const scene::Scene& s, const std::string& case_dir, int np);
  // Written times after `after` (strictly), from the case or processor0.
  std::vector<TimeDir> times_after(double after) const;
  // Throws NonPhysicalState when a field is not finite or rho, p <= 0.
  Snapshot read(const TimeDir& t) const;
  long cells() const;
  const std::vector<Mesh2D>& parts() const { return parts_; }

 private:
  std::string case_dir_;
  std::vector<std::string> part_dirs_;
  std::vector<Mesh2D> parts_;
  std::optional<ShockProbe> probe_;
  bool wedge_ = false;
  double wedge_length_ = 1.0;
  double p_inf_ = 1.0;
};

// Measures between two snapshots, normalised per flow-through time.
HistoryRow compare(const Snapshot& prev, const Snapshot& cur, const std::vector<Mesh2D>& parts,
                   double rho_inf, double flow_through);

// history.csv and, with gnuplot, history.png next to it.
void write_history(const std::string& case_dir, const std::vector<HistoryRow>& rows, double steady_tol,
                   double force_tol, bool plot);

}  // namespace cfd
