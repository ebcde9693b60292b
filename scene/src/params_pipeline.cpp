#include "params_parse.hpp"

namespace scene {

PipelineParams parse_pipeline(Section& s) {
  PipelineParams p;
  p.levels = s.numbers("levels", p.levels, {0.0, 1000.0, true, false});
  p.calibration = s.string("calibration", p.calibration);
  p.cfd = s.boolean("cfd", p.cfd);
  p.reference_grid = s.boolean("reference_grid", p.reference_grid);
  p.reference_level = s.opt_number("reference_level", {0.0, 1000.0, true, false});
  p.budget_cpu_seconds = s.number("budget_cpu_seconds", p.budget_cpu_seconds, positive());
  return p;
}

void emit_pipeline(YAML::Emitter& e, const PipelineParams& p) {
  e << YAML::BeginMap;
  emit_seq(e, "levels", p.levels);
  emit_kv(e, "calibration", p.calibration);
  emit_kv(e, "cfd", p.cfd);
  emit_kv(e, "reference_grid", p.reference_grid);
  emit_opt(e, "reference_level", p.reference_level);
  emit_kv(e, "budget_cpu_seconds", p.budget_cpu_seconds);
  e << YAML::EndMap;
}

}  // namespace scene
