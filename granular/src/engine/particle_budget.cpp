#include "granular/particle_budget.hpp"

#include <cmath>
#include <sstream>

#include "scene/errors.hpp"

namespace granular {

void check_particle_budget(double particles, int engines, const std::string& where) {
  const double total = particles * std::max(engines, 1);
  if (std::isfinite(total) && particles <= kMaxParticles) return;
  std::ostringstream os;
  os.precision(3);
  os << where << "about " << particles << " disks per run";
  if (engines > 1) os << " (x" << engines << " runs at once)";
  os << " would need ~" << total * kBytesPerParticle / 1e9 << " GB; the limit is " << kMaxParticles
     << " disks per run: use fewer particles, a smaller body_diameters or a lower packing fraction";
  throw scene::InputError(os.str());
}

}  // namespace granular
