#pragma once
// The 95% interval of a granular shock's angle (attached) or standoff
// (detached) from the run's averaging groups (about 8, each a few
// interleaved half flow-through slices of one replica): the pooled fit's
// shock found again on each group's fields with its stations, and the
// groups' standard error of the mean, times Student's t with groups - 1
// degrees of freedom, as the half-width (batch means). It estimates what
// another run with other seeds would give (seed-to-seed truth,
// docs/shockfit.md "Interval coverage") and shrinks as the run averages
// longer, where the bootstrap over stations also counts the shock's
// repeatable curvature as noise and stays as wide.
// Attached shocks also find each group's shock from scratch (its own
// stations and tests); the same t times the standard error of those angles
// is the least half-width, and their mean the angle. The pooled fit's
// station choices near the apex are made once per run and every group
// refitted on its stations shares them: on unseen wedges at calibrated e the
// pooled angle spread 0.30 deg from run to run against intervals of
// 0.11-0.15.
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

// Two-sided 95% quantile of the normal distribution: a reported 95%
// half-width over the standard deviation it stands for, where the degrees of
// freedom behind it are not carried along (calibration, prediction bands).
inline constexpr double kNormal95 = 1.96;

// Replaces r's interval by the groups' (relocate_value on each group's
// fields; attached, at least that of the groups' own fits); sets
// r.interval_method ("groups", or "bootstrap" where too few groups find the
// shock again), r.interval_groups, r.interval_group_values and (attached)
// r.group_own_angles. An attached angle becomes the groups' own fits' mean
// (outliers left out; the pooled one kept as r.shock_angle_pooled_deg), a
// standoff the groups' mean (the pooled one kept as r.standoff_pooled).
void apply_group_interval(const scene::Scene& s, const std::vector<scene::Lattice>& groups,
                          ShockResult& r);

}  // namespace shockfit
