#include "steady_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace cfd {

namespace {
// Slack on min_time, in flow-through times (written times are rounded).
constexpr double kMinTimeSlack = 1e-6;

// Checks per plateau window, and how much the density change must still be
// falling from one window to the next to count as converging.
constexpr std::size_t kPlateauChecks = 5;
constexpr double kStillFalling = 0.8;
}  // namespace

SteadyCriteria SteadyCriteria::time_accurate(const scene::CfdParams& p) {
  SteadyCriteria c;
  c.steady_tol = p.steady_tol;
  c.force_tol = p.force_tol;
  c.min_time = p.min_time;
  c.steady_checks = p.steady_checks;
  c.clock = SteadyClock::flow_throughs;
  return c;
}

SteadyCriteria SteadyCriteria::iteration_windows(const scene::CfdParams& p,
                                                 long steps_per_flow_through) {
  SteadyCriteria c = time_accurate(p);
  c.clock = SteadyClock::iterations;
  c.steps_per_flow_through = std::max(1L, steps_per_flow_through);
  return c;
}

// A converged shock solution does not bring the density change to zero: cells
// in the captured shock flicker (rhoCentralFoam's limiter), leaving a floor
// that grows with shock strength (0.03 per flow-through at Mach 3, 0.05 at
// Mach 5, 0.15 at Mach 8) while the body force is steady to 1e-3. So a run is
// also steady once the density change has stopped falling (the mean over the
// last window is no less than kStillFalling times the window before's) and
// the body force over the last window stays within force_tol of its mean.
bool at_noise_floor(const std::vector<HistoryRow>& rows, double force_tol) {
  if (rows.size() < 2 * kPlateauChecks) return false;
  const auto last = rows.end() - static_cast<std::ptrdiff_t>(kPlateauChecks);
  const auto before = last - static_cast<std::ptrdiff_t>(kPlateauChecks);
  double now = 0, prev = 0, fmin = 1e300, fmax = -1e300, fmean = 0;
  for (auto it = last; it != rows.end(); ++it) {
    now += it->drho_l2;
    const double f = scene::norm(it->force);
    fmin = std::min(fmin, f);
    fmax = std::max(fmax, f);
    fmean += f / static_cast<double>(kPlateauChecks);
  }
  for (auto it = before; it != last; ++it) prev += it->drho_l2;
  return now >= kStillFalling * prev && fmax - fmin <= force_tol * std::abs(fmean);
}

double SteadyState::progress(const HistoryRow& row) const {
  if (c_.clock == SteadyClock::iterations)
    return static_cast<double>(row.steps) / static_cast<double>(c_.steps_per_flow_through);
  return row.flow_throughs;
}

void SteadyState::add(const HistoryRow& row) {
  rows_.push_back(row);
  const char* unit =
      c_.clock == SteadyClock::iterations ? "iteration flow-throughs" : "flow-throughs";
  const double at = progress(row);
  const bool early = at < c_.min_time - kMinTimeSlack;
  const bool below_tol = row.drho_l2 < c_.steady_tol && row.dforce < c_.force_tol;
  const bool plateau = !below_tol && at_noise_floor(rows_, c_.force_tol);
  const bool ok = !early && (below_tol || plateau);
  consecutive_ = ok ? consecutive_ + 1 : 0;
  if (steady_) return;
  if (early) {
    why_ = fmt::format("too early: {:.3g} of {:.3g} {}", at, c_.min_time, unit);
  } else if (ok) {
    why_ = fmt::format(
        "{} ({} of {} checks): {}", consecutive_ >= c_.steady_checks ? "steady" : "passing",
        consecutive_, c_.steady_checks,
        below_tol ? fmt::format("drho {:.3g} < {:.3g}, dF {:.3g} < {:.3g}", row.drho_l2,
                                c_.steady_tol, row.dforce, c_.force_tol)
                  : "density change at its noise floor, body force within force_tol");
  } else {
    why_ = fmt::format("changing: drho {:.3g} (tol {:.3g}), dF {:.3g} (tol {:.3g}) at {:.3g} {}",
                       row.drho_l2, c_.steady_tol, row.dforce, c_.force_tol, at, unit);
  }
  steady_ = consecutive_ >= c_.steady_checks;
}

}  // namespace cfd
