#pragma once
// A blunt shape's station bias (calibration.hpp, BowStationBias): fitted on
// training bodies of the shape run at the blunt law, judged by leaving each
// body out, and taken out of a prediction's stations and standoff
// (docs/calibration.md, "The bow shock's fold").
#include <optional>
#include <string>
#include <vector>

#include "pipeline/bow_shock_scatter.hpp"
#include "pipeline/calibration.hpp"
#include "scene/shock_csv.hpp"
#include "scene/vec2.hpp"

namespace pipeline {

// Coefficients of a model ("inclination": b0, b1; "inclination_mach": b0,
// b1, b2; "inclination2_mach": b0, b1, b2, b3); 0 for an unknown name. Its
// formula, for the table ("" when unknown), and the models' names, for errors.
std::size_t station_bias_coefficients(const std::string& model);
std::string station_bias_formula(const std::string& model);
std::string station_bias_models();
// The standoff term's models ("none": q = 0; "constant": a0; "inverse_mach2":
// a0 + a1/M^2): coefficient count (kUnknownStandoffModel for an unknown
// name), formula ("" when unknown) and the names, for errors.
inline constexpr std::size_t kUnknownStandoffModel = static_cast<std::size_t>(-1);
std::size_t standoff_term_coefficients(const std::string& model);
std::string standoff_term_formula(const std::string& model);
std::string standoff_term_models();

// The angle (deg, 0-180) between an outward body normal and the upstream
// direction (-x: the stream flows along +x). NaN for a non-finite normal.
double inclination_deg(scene::Vec2 normal);

// Each model fitted to the bodies' stations (each body's stations weighing
// as much in all as another body's; several runs of one body, same name and
// Mach number, pooled as that body), judged by leaving each body out; the
// one with the smaller left-out RMS (the simpler on a tie). Then the
// standoff's own term on top of it, likewise the one with the smallest
// left-out standoff RMS (each body left out of the fold and the term). nullopt with
// fewer than kMinBiasBodies bodies, a body without inclinations or standoff,
// or where no model's corrected distances stay positive (1 + r above
// kMinBiasDenominator) over the training range. The caller keeps it only
// where relative_rms beats uncorrected_rms.
inline constexpr std::size_t kMinBiasBodies = 3;
inline constexpr double kMinBiasDenominator = 0.5;
std::optional<BowStationBias> fit_station_bias(const std::string& shape,
                                               const std::vector<StationErrors>& runs);

// The stations with the bias taken out: each distance and its interval
// divided by 1 + r(mach, inclination), the shock point moved along its
// normal to match. Rows without a finite normal or distance are left as
// they are.
std::vector<scene::ShockCsvRow> unbiased_stations(const std::vector<scene::ShockCsvRow>& rows,
                                                  const BowStationBias& b, double mach);
// The factor a standoff (and its interval) is multiplied by:
// 1 / ((1 + r(mach, 0)) (1 + q(mach))), q the standoff's own term.
double unbiased_standoff_factor(const BowStationBias& b, double mach);

// The RMS of the training bodies' left-out standoff errors (relative): how
// far a corrected standoff misses the gas's beyond its own interval. NaN
// without bodies.
double left_out_standoff_rms(const BowStationBias& b);

}  // namespace pipeline
