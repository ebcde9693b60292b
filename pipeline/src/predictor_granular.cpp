// The granular gas streamed past the body, its shock located by shockfit's
// two-line fits: the project's predictor.
//
// An attached shock is handed to meshgen as the ray from the apex at the
// fitted angle, not as the fitted stations: the granular shock is thick and
// stands off the apex (its gas is rarefied at the leading edge), so the
// stations lie upstream of the gas shock by 0.02-0.07 body lengths on the
// wedge case studies (4-14 of their finest h_min) while their fitted angle,
// the quantity the restitution is calibrated on, is within a degree. The
// inviscid shock starts at the apex; a band round the stations missed it,
// and the clustered grids' error stalled where the shock ran through graded
// cells (docs/meshgen.md, "The band on an attached shock").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "json_fields.hpp"
#include "pipeline/bow_station_bias.hpp"
#include "pipeline/predictors.hpp"
#include "pipeline/run.hpp"
#include "pipeline/stage_cache.hpp"
#include "scene/body.hpp"
#include "scene/shock_csv.hpp"

namespace pipeline {

namespace {

// What stopped the granular averaging, at what precision and cost
// (docs/granular_flow.md, "Precision on demand").
nlohmann::json averaging_report(const nlohmann::json& r) {
  const nlohmann::json g = r.value("granular", nlohmann::json::object());
  const nlohmann::json precision = g.value("precision", nlohmann::json());
  auto from = [](const nlohmann::json& j, const char* key) {
    return j.is_object() && j.contains(key) ? j[key] : nlohmann::json(nullptr);
  };
  return {{"stopped_by", from(g, "stopped_by")},
          {"flow_throughs", from(g, "averaging_flow_throughs")},
          {"cpu_seconds", from(g, "cpu_seconds")},
          {"cpu_budget", from(g, "cpu_budget")},
          {"target_half_width", from(precision, "target_half_width")},
          {"target_unit", from(precision, "target_unit")},
          {"target_source", from(precision, "target_source")},
          // The last check's, in the target's unit; without a target the
          // shock position's (body lengths).
          {"half_width", precision.is_object() ? from(precision, "half_width")
                                               : from(r, "shock_position_half_width")},
          {"interval_method", from(r, "interval_method")},
          {"interval_groups", from(r, "interval_groups")}};
}

}  // namespace

Prediction GranularPredictor::predict(const PredictContext& cx) const {
  const nlohmann::json r =
      run_prediction(cx.scene, cx.out_dir, cx.np, cx.force, cx.calibration_angle_scatter_deg);
  Prediction p;
  p.predictor = name();
  p.kind = scene::shock_kind_from(r.value("shock", "none"));
  p.shock_angle_deg = number_or_nan(r, "shock_angle_deg");
  p.shock_angle_ci_deg = number_or_nan(r, "shock_angle_ci_deg");
  p.standoff = number_or_nan(r, "standoff");
  p.standoff_ci = number_or_nan(r, "standoff_ci");
  p.cpu_seconds = number_or_nan(r, "predictor_cpu_seconds");
  p.wall_seconds = number_or_nan(r, "granular_wall_seconds");
  p.fingerprint = r.value("fingerprint", "");
  p.shock_csv = cx.out_dir + "/shockfit/shock.csv";
  const double band_ci =
      band_angle_half_width_deg(p.shock_angle_ci_deg, cx.calibration_angle_scatter_deg);
  double bow_rel = scene::kNaN;  // the bow-shock scatter the band used (detached only)
  if (p.kind == scene::ShockKind::attached && std::isfinite(p.shock_angle_deg)) {
    const ShockCurve ray =
        apex_ray(scene::scene_domain(cx.scene), scene::make_body(*cx.scene.body).nose,
                 p.shock_angle_deg, band_ci);
    // The band is part of the prediction: grids meshed round another band are stale.
    p.fingerprint = fingerprint({p.fingerprint, fmt::format("band {:.17g}", band_ci)});
    p.curve = ray.points;
    p.half_width = ray.half_width;
    p.shock_csv = cx.out_dir + "/shock_ray.csv";
    write_shock_curve(p.shock_csv, p.curve, p.half_width);
  } else if (p.kind != scene::ShockKind::none &&
             r.value("stations_accepted", std::size_t{0}) < scene::kMinShockCurvePoints) {
    // shockfit saw a shock (its stagnation-line standoff is reported) but
    // accepted too few stations to place a curve: a weak near-sonic shock,
    // or a granular shock far from where the domain expects it. No band:
    // the pipeline runs the uniform family alone and gives no verdict.
    p.details["no_band"] = fmt::format(
        "shockfit accepted {} of {} stations, fewer than the {} a band needs (standoff on the axis "
        "{:.3g} "
        "+- {:.2g} body lengths)",
        r.value("stations_accepted", 0), r.value("stations", 0), scene::kMinShockCurvePoints,
        p.standoff, p.standoff_ci);
  } else if (p.kind != scene::ShockKind::none) {
    // The stations' own intervals say how well this run knows its shock, not
    // how far the calibrated gas is from the ideal gas's: a bow shock's band
    // also covers the table's out-of-sample error of its distances (NaN: none).
    if (p.kind == scene::ShockKind::detached) bow_rel = cx.calibration_bow_shock_relative_rms;
    auto rows = scene::read_shock_csv(p.shock_csv).rows;
    // A bow shock of a shape whose fold the table measured is moved onto
    // where the gas's stands, station by station, before the band is drawn.
    const BowStationBias* bias =
        p.kind == scene::ShockKind::detached ? cx.bow_station_bias : nullptr;
    if (bias) {
      const double mach = cx.scene.freestream.mach;
      rows = unbiased_stations(rows, *bias, mach);
      const double f = unbiased_standoff_factor(*bias, mach);
      p.details["standoff_granular"] = json_number(p.standoff);
      p.details["standoff_granular_ci"] = json_number(p.standoff_ci);
      p.details["station_bias"] = {
          {"shape", bias->shape},
          {"model", bias->model},
          {"coefficients", bias->coefficients},
          {"standoff_model", bias->standoff_model},
          {"standoff_coefficients", bias->standoff_coefficients},
          {"standoff_factor", f},
          {"left_out_standoff_rms", json_number(left_out_standoff_rms(*bias))}};
      p.standoff *= f;
      p.standoff_ci *= f;
      p.fingerprint = fingerprint(
          {p.fingerprint, fmt::format("station bias {} {} standoff {} {}", bias->model,
                                      fmt::join(bias->coefficients, " "), bias->standoff_model,
                                      fmt::join(bias->standoff_coefficients, " "))});
    }
    for (auto& q : rows) {
      if (!q.accepted) continue;
      q.ci = band_bow_half_width(std::isfinite(q.ci) ? q.ci : 0.0, q.distance, bow_rel);
      p.curve.push_back(q.shock);
      p.half_width.push_back(q.ci);
    }
    if (std::isfinite(bow_rel) || bias) {
      // Every station, as shockfit laid them out (so the band can be set
      // against any other shock of the body station by station), each
      // accepted one's ci the band's half-width.
      p.fingerprint = fingerprint({p.fingerprint, fmt::format("bow band {:.17g}", bow_rel)});
      p.shock_csv = cx.out_dir + "/shock_band.csv";
      scene::write_shock_csv(p.shock_csv, rows);
    }
  }
  p.details.update(
      {{"restitution", cx.scene.granular.restitution},
       {"granular", r.value("granular", nlohmann::json::object())},
       {"field", r.value("field", "")},
       {"calibration_angle_scatter_deg", json_number(cx.calibration_angle_scatter_deg)},
       {"band_angle_half_width_deg", json_number(band_ci)},
       {"calibration_bow_shock_relative_rms", json_number(bow_rel)},
       {"averaging", averaging_report(r)}});
  return p;
}

}  // namespace pipeline
