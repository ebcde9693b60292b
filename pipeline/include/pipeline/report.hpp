#pragma once
// DIR/summary.json (contract's pipeline keys) and DIR/report.md with figures.
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/compare.hpp"
#include "scene/scene.hpp"

namespace pipeline {

struct ReportInputs {
  const scene::Scene& scene;
  std::string out_dir;
  nlohmann::json prediction;  // run_prediction's result
  Reference reference;
  Comparison comparison;
  std::string calibration_note;
  double total_seconds = 0;
};

nlohmann::json make_summary(const ReportInputs& in);
void write_report(const ReportInputs& in, const nlohmann::json& summary);

}  // namespace pipeline
