#pragma once
// Constants every stage shares: angle conversion, the missing-value marker
// and the particle size of the granular unit system (docs/units.md).
#include <limits>
#include <numbers>

namespace scene {

// One degree in radians: multiply degrees by it, divide radians by it.
inline constexpr double kDeg = std::numbers::pi / 180.0;

// A quantity that does not apply or was not measured (null in JSON, nan in
// CSV).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Area of one disk in granular units (lengths in particle diameters d, so
// the radius is 1/2): packing fraction = number density x kDiskArea.
inline constexpr double kDiskArea = std::numbers::pi / 4.0;

}  // namespace scene
