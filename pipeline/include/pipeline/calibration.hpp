#pragma once
// The restitution table of `pipeline calibrate`: for each training wedge
// (Mach, angle) the coefficient of restitution at which the granular shock
// angle equals the ideal-gas (gamma 1.4) theta-beta-Mach angle, and the
// smooth model e(M[, theta]) fitted to them (docs/calibration.md).
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/restitution_fit.hpp"
#include "pipeline/restitution_local.hpp"
#include "scene/units.hpp"

namespace pipeline {

// e = 1 is the elastic limit: a fit extrapolated below the training Mach
// numbers (c1 > 0) can exceed it, which no disk collision can.
inline constexpr double kMaxRestitution = 1.0;
// A table's e is applied rounded to this: the resolved scene echoes it
// exactly, so rerunning the resolved scene reproduces the run bit for bit.
inline constexpr double kRestitutionQuantum = 1e-6;
inline double quantised_restitution(double e) {
  return std::round(e / kRestitutionQuantum) * kRestitutionQuantum;
}
// Whether a run's e is the table's `table_e` as applied (rounded to
// kRestitutionQuantum): the e a measure made on the run belongs to.
inline bool is_applied_restitution(double applied, double table_e) {
  return std::abs(table_e - applied) <= 0.5 * kRestitutionQuantum + 1e-12;
}
// Out-of-sample runs use the scene's seed plus this offset; the fits'
// sweeps used seed .. seed + replicas - 1, so an offset above the replica
// count gives replicas no sweep has seen.
inline constexpr std::uint64_t kLeaveOneOutSeedOffset = 1000;
// Seeds per swept e at most, kSeedStride (restitution_crossing.hpp) apart:
// an 11th would reach the left-out checks' seeds.
inline constexpr int kMaxSweepSeeds = 10;

struct CalibrationEntry {
  double mach = 0, angle_deg = 0;
  double restitution = 1, restitution_ci = 0;  // crossing e, 95% half-width
  double gas_angle_deg = 0;                    // theta-beta-Mach target
  double granular_angle_deg = 0;               // measured out of sample (see below)
  double granular_angle_ci_deg = 0;
  // Fitted tables: e of this point predicted by the model refitted without
  // it; granular_angle_deg is measured at that e with a seed the fit never
  // used. Old tables: NaN, and granular_angle_deg is the in-sample rerun at
  // the crossing e.
  double loo_restitution = scene::kNaN;
};
// A training wedge's crossing before any out-of-sample check has measured it
// (those fields NaN).
inline CalibrationEntry crossing_entry(double mach, double angle_deg, double e, double e_ci,
                                       double gas_angle_deg) {
  CalibrationEntry c;
  c.mach = mach;
  c.angle_deg = angle_deg;
  c.restitution = e;
  c.restitution_ci = e_ci;
  c.gas_angle_deg = gas_angle_deg;
  c.granular_angle_deg = c.granular_angle_ci_deg = c.loo_restitution = scene::kNaN;
  return c;
}

// A blunt shape's own restitution, e = c0 + c1/M^2: one e(M) does not
// serve wedges, discs and capsules alike (the wedge fit stands a disc's bow
// shock too far off at Mach 3 and too close at Mach 6, Apollo's too close at
// every Mach number). Fitted, per shape, on the training bodies' crossings:
// the e at which the granular standoff equals the gas's (docs/calibration.md,
// "A restitution per blunt shape"). Two coefficients; a fit needs one body
// more, so that each body's left-out fit exists.
inline constexpr std::size_t kBowShapeCoefficients = 2;
struct BowShapePoint {
  std::string body;  // the training scene's name
  double mach = 0;
  double restitution = 1, restitution_ci = 0;  // the crossing and its 95% half-width
  // e predicted by the shape's fit without this body, and the granular bow
  // shock measured there (fresh seed) against the gas's: mean and RMS
  // relative station error, and the standoff's relative error.
  double loo_restitution = scene::kNaN;
  double loo_mean = scene::kNaN, loo_rms = scene::kNaN, loo_standoff = scene::kNaN;
};
struct BowShapeFit {
  std::string shape;                 // scene::bow_shape_class of the body
  std::vector<double> coefficients;  // c0, c1
  // RMS over the shape's bodies of their left-out station RMS: the band's
  // relative scatter for bodies of this shape.
  double relative_rms = scene::kNaN;
  std::vector<BowShapePoint> points;
  double evaluate(double mach) const;  // clamped to e <= kMaxRestitution
};

// A blunt shape's station bias under the blunt law: the granular bow shock
// at that e folds against the gas's, standing off too far on the stagnation
// line and too close on its wings, by an amount that moves with the
// station's place on the body, not with the body's size. A standoff and a
// wing want different e (docs/calibration.md, "Discs with the
// stagnation-line reference"), so no e serves both; the fold is measured on
// training bodies of the shape and taken out of every station:
//   r = b0 + b1 s [+ b2 / M^2],   s = inclination / 90 deg,
// r the relative distance error (d_granular - d_gas) / d_gas, inclination
// the angle between the station's outward body normal and the upstream
// direction (0 on the stagnation line, 90 deg where the body turns parallel
// to the stream). A corrected distance is d / (1 + r), the standoff's is at
// s = 0. Fitted and judged by leaving each body out (bow_station_bias.hpp).
struct BowStationBiasBody {
  std::string body;
  double mach = scene::kNaN;
  int stations = 0;
  int runs = 1;  // granular runs (seeds) pooled for the body
  // Uncorrected: stations' relative mean and RMS, the standoff's relative
  // error against the gas's stagnation-line standoff.
  double mean = scene::kNaN, rms = scene::kNaN, standoff = scene::kNaN;
  // Corrected by the fit made without this body.
  double loo_mean = scene::kNaN, loo_rms = scene::kNaN, loo_standoff = scene::kNaN;
};
struct BowStationBias {
  std::string shape;  // scene::bow_shape_class of the bodies
  std::string model;  // one of station_bias_models() (bow_station_bias.hpp)
  std::vector<double> coefficients;
  // RMS over bodies of their left-out corrected station RMS: the band's
  // relative scatter for bodies of this shape; and the same bodies'
  // uncorrected RMS, the baseline the fit had to beat.
  double relative_rms = scene::kNaN, uncorrected_rms = scene::kNaN;
  // The training stations' largest inclination and the bodies' Mach
  // numbers: outside them the model is held at their ends.
  double max_inclination_deg = 90.0;
  double mach_low = scene::kNaN, mach_high = scene::kNaN;
  std::vector<BowStationBiasBody> bodies;
  // What its training runs cost (their predictors and the uniform grids
  // compared with), charged to the shape's predictions; NaN: not recorded.
  double cpu_seconds = scene::kNaN;
  // The standoff's own relative error q(M) left after the fold at s = 0 (the
  // standoff is the vertex of a parabola through the near-axis stations, not
  // one station, and its Mach dependence need not be theirs): one of
  // standoff_term_models() (bow_station_bias.hpp), "none" being q = 0,
  // chosen by the bodies' left-out standoff RMS; that RMS per candidate.
  std::string standoff_model = "none";
  std::vector<double> standoff_coefficients;
  std::vector<std::pair<std::string, double>> standoff_left_out_rms;
  double relative_error(double mach, double inclination_deg) const;
  double standoff_error(double mach) const;  // q(M), held at the training Mach ends
};

// The granular bow shock's out-of-sample error under this table's e(M):
// on training blunt bodies (none a case study), the relative error of each
// shockfit station's shock distance against the gas's (the finest steady
// uniform grid of a `pipeline run` of the body). The RMS is over bodies,
// each body's own RMS over its stations counting once (a body's stations
// move together). Measured after the e(M) fit it belongs to: a new fit
// drops it (docs/calibration.md, "The bow shock's band").
struct BowShockScatter {
  double relative_rms = scene::kNaN;
  std::vector<std::string> bodies;  // the training scenes' names
  // Their free-stream Mach numbers, in the same order; empty in tables written
  // before they were recorded (no range can then be checked).
  std::vector<double> machs;
  int stations = 0;  // stations compared, all bodies
  // What the training runs cost (their predictors and the uniform grids
  // compared with); NaN when not recorded.
  double cpu_seconds = scene::kNaN;
  std::vector<BowShapeFit> shapes;  // empty: every blunt body takes the wedge e(M)
  const BowShapeFit* shape(const std::string& name) const;
  // Shapes without an own e whose bodies run at the law and have their fold
  // taken out; a shape with an own e fit has none.
  std::vector<BowStationBias> station_biases;
  const BowStationBias* station_bias(const std::string& name) const;
  // The Mach-only e(M) the training bodies ran at, i.e. the law this scatter
  // was measured under: blunt bodies keep it, and the block stays, when a new
  // wedge calibration replaces the table's fits. Absent in tables written
  // before it was recorded: blunt bodies then take the table's Mach-only fit,
  // and a new wedge fit drops the block.
  std::optional<RestitutionFit> restitution_law;
};

// An attached shock's table error measured where the band uses it: over
// unseen wedges (no training point, no case study) predicted with this
// table at the default averaging, sqrt(mean error^2 - mean (half-width /
// 1.96)^2), error = granular - gas angle (docs/calibration.md, "The band's
// table error"). Written by `pipeline calibrate --angle-check-runs`;
// measured under the fit it belongs to, so a new fit drops it.
struct AngleScatter {
  double deg = scene::kNaN;
  double rms_deg = scene::kNaN;        // the runs' RMS error, their own noise included
  double flow_throughs = scene::kNaN;  // the runs' averaging
  int runs = 0, wedges = 0;
  // The runs' free-stream Mach numbers; NaN in tables written before they
  // were recorded.
  double mach_low = scene::kNaN, mach_high = scene::kNaN;
};

struct CalibrationTable {
  double gamma = 1.4;
  std::vector<CalibrationEntry> entries;  // the training points
  // Empty in an old table (entries only): pipeline run then interpolates.
  std::optional<RestitutionModel> model;  // the chosen one
  std::vector<RestitutionFit>
      fits;  // every candidate (the chosen one and the Mach-only one at least)
  const RestitutionFit* fit(RestitutionModel m) const;
  // The chosen model's local correction (attached wedges only), when the
  // calibration kept one; its residuals are rebuilt from the entries on read.
  std::optional<LocalCorrection> local_correction;
  // CPU seconds the table cost to make (training runs and out-of-sample
  // checks); NaN when not recorded. Reports amortise it over the scenes it serves.
  double cpu_seconds = scene::kNaN;
  std::optional<BowShockScatter> bow_shock;
  std::optional<AngleScatter> angle_scatter;
  // The same error measured where e(M) is extrapolated: unseen wedges all on
  // one side of the training Mach range (inside its deflections). Attached
  // wedges on that side take it in their band; a new fit drops it too.
  std::optional<AngleScatter> angle_scatter_beyond;
};

// Sets the chosen model's local correction at these bandwidths, its
// residuals taken at the entries as the table file holds them, so that a
// table read back evaluates identically.
void attach_local_correction(CalibrationTable& t, double h_log_mach, double h_angle_deg,
                             double loo_rms);

// Chooses the table's chosen model's local correction on `points` (the
// crossings it was fitted to), at `held` widths where given, and, where one
// is kept, attaches it; returns what was kept (nullopt: none).
std::optional<LocalCorrection> keep_local_correction(
    CalibrationTable& t, std::span<const RestitutionPoint> points,
    const std::optional<CorrectionWidths>& held = std::nullopt);

CalibrationTable read_calibration(
    const std::string& path);  // InputError (file and key) if malformed
// Coefficients are written to 17 significant digits (they round-trip exactly).
void write_calibration(const CalibrationTable& t, const std::string& path);
// The RMS of the out-of-sample angle errors (granular_angle_deg -
// gas_angle_deg, each measured at its leave-one-out restitution) over the
// entries that have one: how far a prediction from this table misses the gas
// angle, the run's own noise included. NaN for an old table (its reruns are
// in sample) or fewer than two such entries.
double out_of_sample_angle_rms_deg(const CalibrationTable& t);
// The table's own error in the angle, the scatter an attached shock's band
// adds: the measured `angle_scatter` where the table has one, else that RMS
// with the left-out runs' own noise (each run's 95% interval / 1.96) taken
// out in quadrature, floored at zero. A new run's interval already holds its
// own noise; counting the left-out runs' noise again in the band would count
// it twice. (The left-out runs average 4 flow-through times, and their
// intervals over-state their noise: 0.10 deg from them against 0.16-0.18
// measured on unseen wedges at 16.) NaN where neither is.
double table_angle_scatter_deg(const CalibrationTable& t);
// The scatter a wedge at this Mach number takes: `angle_scatter_beyond` where
// the Mach number lies beyond scatter_mach_range on the side that block was
// measured (never narrower than the inside scatter), else the one above.
double table_angle_scatter_deg(const CalibrationTable& t, double mach);
// Whether `angle_scatter_beyond` is what a wedge at this Mach number takes.
bool beyond_scatter_applies(const CalibrationTable& t, double mach);

// The Mach-only fit that bodies without a wedge angle take: the bow block's
// recorded law, else the chosen model when it ignores the angle, else the
// inverse_mach2 fit. nullptr for an old table (entries only).
const RestitutionFit* blunt_restitution_law(const CalibrationTable& t);

// What a new wedge calibration keeps of the table it replaces: the bow
// block when it records the e(M) its bodies ran at (it does not depend on
// the wedge fit, and blunt bodies keep that law), else nothing (it was
// measured under the fit being replaced).
std::optional<BowShockScatter> bow_shock_kept_by_wedge_fit(const CalibrationTable& old);
// The same for the table at `path` about to be replaced (nothing when there
// is none yet); InputError if that table is malformed.
std::optional<BowShockScatter> bow_shock_kept_by_wedge_fit(const std::string& path);

// The restitution for a body at (mach, angle_deg). A fitted table evaluates
// its model, clamped to e <= 1; a NaN angle (blunt bodies) takes
// blunt_restitution_law, an extrapolation from wedges. An old table interpolates
// by inverse distance in (Mach, angle) scaled by (1, 5 deg) (an exact match
// returns its entry's e; a NaN angle weighs the entries by Mach alone).
// nullopt for an empty table.
std::optional<double> interpolate_restitution(const CalibrationTable& t, double mach,
                                              double angle_deg);

// The Mach numbers the table's training entries span, {lowest, highest};
// nullopt for an empty table. Outside it e(M) is an extrapolation whose
// error no run has measured.
struct MachRange {
  double low = 0, high = 0;
  bool contains(double mach) const { return mach >= low && mach <= high; }
};
std::optional<MachRange> training_mach_range(const CalibrationTable& t);
// The Mach range the inside `angle_scatter` describes: the Mach numbers of
// the runs it was measured on where it records them, else the training range.
// A table extended beyond those runs (`--extend`) has training wedges there
// whose error the inside scatter never saw.
std::optional<MachRange> scatter_mach_range(const CalibrationTable& t);
// The training wedges' deflections (deg), in the same type; nullopt without entries.
std::optional<MachRange> training_angle_range(const CalibrationTable& t);
// The same for a shape's fit: its training bodies' Mach numbers.
MachRange training_mach_range(const BowShapeFit& f);
// The same for the bow block's scatter: the Mach numbers of the blunt bodies
// it was measured on; nullopt where the block does not record them.
std::optional<MachRange> training_mach_range(const BowShockScatter& w);

}  // namespace pipeline
