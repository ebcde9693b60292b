// The granular gas streamed past the body, its shock located by shockfit's
// two-line fits: the project's predictor.
#include "pipeline/predictors.hpp"

#include <cmath>

#include "json_fields.hpp"
#include "pipeline/run.hpp"

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
          {"half_width", from(r, "shock_position_half_width")}};
}

}  // namespace

Prediction GranularPredictor::predict(const PredictContext& cx) const {
  const nlohmann::json r = run_prediction(cx.scene, cx.out_dir, cx.np, cx.force);
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
  if (p.kind != scene::ShockKind::none)
    for (const auto& q : read_accepted_shock(p.shock_csv)) {
      p.curve.push_back(q.point);
      p.half_width.push_back(q.half_width);
    }
  p.details = {{"restitution", cx.scene.granular.restitution},
               {"granular", r.value("granular", nlohmann::json::object())},
               {"field", r.value("field", "")},
               {"averaging", averaging_report(r)}};
  return p;
}

}  // namespace pipeline
