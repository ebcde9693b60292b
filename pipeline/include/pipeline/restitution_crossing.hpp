#pragma once
// Where the granular shock angle, swept over e, crosses the gas angle; and
// which e to run next to sharpen that crossing.
#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace pipeline {

// Swept e (wedge angles and blunt standoffs alike) are rounded to this step,
// clamped to the elastic limit: the cache directories are named by e, and an
// e within half a step of a run is that run.
inline constexpr double kSweepRestitutionStep = 1e-4;
double swept_restitution(double e);

// One run of a sweep: e, the granular shock angle and its 95% half-width (deg).
struct SweepPoint {
  double e = 1, angle = 0, ci = 0;
};

// A run counts only when shockfit found a physical attached angle with a
// usable interval (a failed fit can return any number; a misfit classed
// "detached" has none).
bool usable(const SweepPoint& p);

struct Crossing {
  double e = 1, e_ci = 0;        // 95% half-width, the angle intervals through the local slope
  double e_low = 1, e_high = 1;  // the bracketing runs
};
// Linear interpolation of e where angle(e) crosses `target`, between
// neighbouring usable runs (an unusable run in between is skipped, not a
// break), scanning from the largest e downwards: the physically relevant,
// least dissipative crossing. `pts` sorted by e.
std::optional<Crossing> find_crossing(const std::vector<SweepPoint>& pts, double target);

// Whether find_crossing's bracket is a step of angle(e): where angle(e) is
// smooth it is convex below e = 1 (each segment of a sweep rises no faster
// than the one above it), and a bracket that rises several times faster than
// the segment above it, by more than its two runs' intervals allow, breaks
// that. On a step the gas angle is met only at its foot, and an e a little
// lower reads degrees lower (docs/calibration.md "The averaging the crossings
// are read at"). False where there is no crossing or no usable run above it.
bool crossing_on_step(const std::vector<SweepPoint>& pts, double target);

// Where a straight line through the usable runs within `window` of
// find_crossing's e meets `target`: several noisy runs pin a crossing
// better than the two that bracket it (a blunt body's granular standoff
// scatters by several percent from run to run). Weights 1/ci^2; the 95%
// half-width is the line's, through its intercept and slope, scaled up by
// the residuals where they scatter more than the runs' intervals say.
// find_crossing's answer with fewer than three runs in the window, or
// where the line is flat, slopes against the bracket, or meets `target`
// outside the window.
std::optional<Crossing> find_crossing_by_line(const std::vector<SweepPoint>& pts, double target,
                                              double window);

// Where a parabola through the usable runs within `window` of
// find_crossing's e meets `target`: angle(e) is convex below e = 1, so a
// chord or a line across the crossing puts it too low (M4.5/14: 24.1, 25.2
// and 26.5 deg at e = 0.97, 0.975, 0.98, a chord over 0.01 reads 0.2 deg
// high at its middle). Weights 1/ci^2; the 95% half-width from the fit's
// covariance through the root, scaled up by the residuals where there are
// more runs than coefficients and they scatter more than their intervals
// say. find_crossing_by_line's answer with fewer than three runs, or where
// the parabola turns between the bracketing runs, runs against them or
// meets `target` outside the window.
std::optional<Crossing> find_crossing_by_curve(const std::vector<SweepPoint>& pts, double target,
                                               double window);

// Runs of one e at several seeds: the inverse-variance weighted mean of the
// usable ones and its 95% half-width (a run whose fit went astray says so
// with a wide interval, and so counts little). None usable: NaN.
SweepPoint mean_point(double e, const std::vector<SweepPoint>& runs);

// A training body's k-th seed (k = 0: its own). A run's replicas take
// consecutive seeds from its own, so seeds this far apart share no replica.
inline constexpr std::uint64_t kSeedStride = 100;
std::uint64_t nth_seed(std::uint64_t base, int k);
// The cache directory of the k-th seed's run beside `dir`, the first seed's.
std::string seed_dir(const std::string& dir, int k, std::uint64_t seed);

// One swept e at `seeds` seeds (nth_seed of `base_seed`, each run cached in
// seed_dir of `dir`): `run(seed, dir)` makes one run and returns its point
// and its JSON record. Their mean_point goes into `pts` (kept sorted by e)
// and is returned with the records.
struct SeedRuns {
  SweepPoint mean;
  nlohmann::json records;
};
template <class Run>
SeedRuns run_at_seeds(double e, int seeds, std::uint64_t base_seed, const std::string& dir,
                      std::vector<SweepPoint>& pts, Run run) {
  std::vector<SweepPoint> runs;
  SeedRuns out{{}, nlohmann::json::array()};
  for (int k = 0; k < seeds; ++k) {
    const std::uint64_t seed = nth_seed(base_seed, k);
    auto [point, record] = run(seed, seed_dir(dir, k, seed));
    runs.push_back(point);
    out.records.push_back(std::move(record));
  }
  out.mean = mean_point(e, runs);
  pts.push_back(out.mean);
  std::sort(pts.begin(), pts.end(),
            [](const SweepPoint& a, const SweepPoint& b) { return a.e < b.e; });
  return out;
}

// The next e to run: the midpoint of the bracketing interval (a chord
// across the convex angle(e) puts the crossing too low); without a crossing,
// a step towards the gas angle: halfway to the nearest run beyond the usable
// ones (unusable there), else one sweep step beyond them (never above e = 1).
// nullopt when that e has been run or nothing lies in that direction.
// Rounded to 1e-4 (the cache directories are named by e).
std::optional<double> next_restitution(const std::vector<SweepPoint>& pts, double target);

}  // namespace pipeline
