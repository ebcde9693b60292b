// The granular gas streamed past the body, its shock located by shockfit's
// two-line fits: the project's predictor.
#include "pipeline/predictors.hpp"

#include <cmath>

#include "json_fields.hpp"
#include "pipeline/run.hpp"

namespace pipeline {

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
               {"field", r.value("field", "")}};
  return p;
}

}  // namespace pipeline
