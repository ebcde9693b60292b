#pragma once
// The 95% interval of a granular shock's angle (attached) or standoff
// (detached) from the run's averaging groups: the shock found with the same
// stations on each group's fields alone (about 8 groups, each a few
// interleaved half flow-through slices of one replica), and the groups'
// standard error of the mean, times Student's t with groups - 1 degrees of
// freedom, as the half-width (batch means). It estimates what another run
// with other seeds would give (seed-to-seed truth, docs/shockfit.md
// "Interval coverage") and shrinks as the run averages longer, where the
// bootstrap over stations also counts the shock's repeatable curvature as
// noise and stays as wide.
#include <vector>

#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "shockfit/locate.hpp"

namespace shockfit {

// Fewest groups that find the shock again for a group interval; with fewer
// r keeps its bootstrap interval.
inline constexpr int kMinIntervalGroups = 4;

// Two-sided 95% quantile of Student's t with `dof` degrees of freedom (>= 1).
double student_t95(int dof);

// Replaces r's interval by the groups' (relocate_value on each group's
// fields); sets r.interval_method ("groups", or "bootstrap" where too few
// groups find the shock again) and r.interval_groups.
void apply_group_interval(const scene::Scene& s, const std::vector<scene::Lattice>& groups,
                          ShockResult& r);

}  // namespace shockfit
