#pragma once
// Equation of state of the hard-disk fluid, shared by the engine (inflow
// pressure of its reservoirs) and the flow measurement (pressure fields,
// sound speed).
#include <cmath>

namespace granular {

// Henderson's compressibility factor Z = p / (n T) = (1 + nu^2/8) / (1 - nu)^2
// at packing fraction nu, accurate to ~1% up to nu ~ 0.6.
constexpr double henderson_z(double nu) {
  return (1.0 + nu * nu / 8.0) / ((1.0 - nu) * (1.0 - nu));
}
// Its derivative dZ/dnu.
inline double henderson_dz(double nu) {
  return (nu / 4.0) / ((1.0 - nu) * (1.0 - nu)) +
         2.0 * (1.0 + nu * nu / 8.0) / std::pow(1.0 - nu, 3);
}

}  // namespace granular
