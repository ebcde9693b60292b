#include "granular/precision_stop.hpp"

#include <algorithm>
#include <cmath>

namespace granular {

namespace {

// Check i against the latest check at or before half its averaging time.
bool stalled(const std::vector<PrecisionCheck>& checks, std::size_t i) {
  const PrecisionCheck& now = checks[i];
  if (!std::isfinite(now.half_width)) return false;
  for (std::size_t j = i; j-- > 0;) {
    const PrecisionCheck& then = checks[j];
    if (then.flow_throughs > 0.5 * now.flow_throughs) continue;
    return std::isfinite(then.half_width) && then.half_width > 0.0 &&
           then.quantity == now.quantity && now.half_width >= kPlateauRatio * then.half_width &&
           now.half_width <= kGrowthRatio * then.half_width;
  }
  return false;
}

}  // namespace

bool interval_plateaued(const std::vector<PrecisionCheck>& checks) {
  const std::size_t n = checks.size();
  return n >= 2 && checks[n - 1].quantity == checks[n - 2].quantity && stalled(checks, n - 1) &&
         stalled(checks, n - 2);
}

double expected_saving(const std::function<double(double, double)>& downstream, double value,
                       double half_width, double averaged, double more) {
  if (!downstream || !(averaged > 0.0) || !(more > 0.0)) return std::nan("");
  const double most = downstream(value, half_width) - downstream(value, 0.0);
  if (std::isnan(most)) return most;
  return std::max(most, 0.0) * (1.0 - std::sqrt(averaged / (averaged + more)));
}

bool chunk_pays(double expected_saving_cpu, double chunk_cpu) {
  return !(expected_saving_cpu < chunk_cpu);
}

}  // namespace granular
