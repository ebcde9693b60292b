#pragma once
// The restitution table of `pipeline calibrate`: for each (Mach, wedge angle)
// the coefficient of restitution at which the granular shock angle equals
// the ideal-gas (gamma 1.4) theta-beta-Mach angle.
#include <optional>
#include <string>
#include <vector>

namespace pipeline {

struct CalibrationEntry {
  double mach = 0, angle_deg = 0;
  double restitution = 1, restitution_ci = 0;  // 95% half-width
  double gas_angle_deg = 0;                    // theta-beta-Mach target
  double granular_angle_deg = 0;               // measured at the calibrated e (verification run)
  double granular_angle_ci_deg = 0;
};

struct CalibrationTable {
  double gamma = 1.4;
  std::vector<CalibrationEntry> entries;
};

CalibrationTable read_calibration(const std::string& path);  // InputError if malformed
void write_calibration(const CalibrationTable& t, const std::string& path);
// Inverse-distance interpolation in (Mach, angle) scaled by (1, 5 deg); an
// exact match returns its entry's e. A NaN angle (blunt bodies) weighs the
// entries by Mach number alone. nullopt for an empty table.
std::optional<double> interpolate_restitution(const CalibrationTable& t, double mach, double angle_deg);

}  // namespace pipeline
