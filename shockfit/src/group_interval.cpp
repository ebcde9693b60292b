#include "shockfit/group_interval.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace shockfit {

double student_t95(int dof) {
  static constexpr std::array<double, 30> kTable = {
      12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
      2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
      2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::numeric_limits<double>::infinity();
  if (dof <= static_cast<int>(kTable.size())) return kTable[static_cast<std::size_t>(dof - 1)];
  return 1.959963984540054 + 2.4 / dof;  // within 0.002 of the quantile beyond 30
}

void apply_group_interval(const scene::Scene& s, const std::vector<scene::Lattice>& groups,
                          ShockResult& r) {
  r.interval_method = "bootstrap";
  r.interval_groups = 0;
  if (r.shock != scene::ShockKind::attached && r.shock != scene::ShockKind::detached) return;
  std::vector<double> values;
  for (const scene::Lattice& lat : groups) {
    const double v = relocate_value(s, lat, r);
    if (std::isfinite(v)) values.push_back(v);
  }
  const int g = static_cast<int>(values.size());
  if (g < kMinIntervalGroups) return;
  double mean = 0.0;
  for (const double v : values) mean += v / g;
  double ss = 0.0;
  for (const double v : values) ss += (v - mean) * (v - mean);
  // The full run's value is (near) the groups' mean: its standard error is
  // the groups' standard deviation over sqrt(g).
  const double half = student_t95(g - 1) * std::sqrt(ss / (g - 1.0) / g);
  r.interval_method = "groups";
  r.interval_groups = g;
  if (r.shock == scene::ShockKind::attached) {
    r.shock_angle_ci_deg = half;
    r.shock_angle_lo_deg = r.shock_angle_deg - half;
    r.shock_angle_hi_deg = r.shock_angle_deg + half;
  } else {
    r.standoff_ci = half;
  }
}

}  // namespace shockfit
