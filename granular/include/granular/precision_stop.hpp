#pragma once
// When precision on demand stops averaging: the goal met, or the shock's
// interval no longer shrinking with averaging time.
#include <functional>
#include <string>
#include <vector>

namespace granular {

// One precision check: averaging time so far (flow-through times), the
// shock position's 95% half-width (body lengths; NaN when no shock was
// found) and the quantity it came from ("shock_angle", "standoff").
struct PrecisionCheck {
  double flow_throughs = 0;
  double half_width = 0;
  std::string quantity;
};

// Statistical averaging narrows an interval as 1/sqrt(time): doubling the
// time takes it to 0.71 of its width. An interval still above
// kPlateauRatio of its width at half the time is held up by something
// averaging does not reduce (the lattice's resolution of the shock, the fit
// itself), so more averaging buys almost nothing.
inline constexpr double kPlateauRatio = 0.9;
// An interval that grew beyond this factor of its width at half the time is
// no floor: the shock is still settling (the averaging groups then hold
// different mixes of early and late slices; disc M3.5: 0.050, 0.037, 0.066,
// 0.097 at 1-2.5 flow-through times, 0.025 at 4), and averaging on helps.
inline constexpr double kGrowthRatio = 1.5;

// The last two checks each hold at least kPlateauRatio, and at most
// kGrowthRatio, of the half-width of the latest check at or before half
// their averaging time, all with the same
// quantity and finite widths. Two, because one interval moves by 10-20%
// from check to check.
bool interval_plateaued(const std::vector<PrecisionCheck>& checks);

// What averaging `more` flow-through times beyond `averaged` is expected to
// save the later stages, CPU seconds. The most any averaging could save is
// downstream(value, half_width) - downstream(value, 0), an exact shock's
// (none where that is negative). The next chunk is expected to take the
// half-width to half_width sqrt(averaged / (averaged + more)), the
// statistical 1/sqrt(time), and to save that fraction of the most: a secant,
// since the later stages' cost moves in steps with the half-width (meshgen
// cuts its strips where the band doubles), and a difference over one chunk's
// small narrowing would read the steps, not the trend. NaN where nothing is
// priced, nothing is averaged yet or either price is NaN.
double expected_saving(const std::function<double(double, double)>& downstream, double value,
                       double half_width, double averaged, double more);

// A chunk pays when what it is expected to save exceeds its own CPU seconds.
// Averaging stops on the second check in a row at which the next chunk would
// not pay: the interval moves by 10-20% from check to check, and with it the
// projected saving. A saving that cannot be priced (NaN) counts as paying.
inline constexpr int kUnpaidChecksToStop = 2;
bool chunk_pays(double expected_saving_cpu, double chunk_cpu);

}  // namespace granular
