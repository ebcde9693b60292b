#pragma once
// DIR/summary.json (contract's pipeline keys) and DIR/report.md with figures.
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/compare.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/verdict.hpp"
#include "scene/scene.hpp"

namespace pipeline {

struct ReportInputs {
  const scene::Scene& scene;
  std::string out_dir;
  Prediction prediction;
  Reference reference;
  Comparison comparison;
  Verdict verdict;
  std::string calibration_note;
  double total_seconds = 0;
  nlohmann::json grid_convergence;  // reference grid and Richardson estimates (null when none ran)
};

nlohmann::json make_summary(const ReportInputs& in);
void write_report(const ReportInputs& in, const nlohmann::json& summary, const std::string& file_name = "report.md");

// One line for the terminal: the verdict with its interval.
std::string verdict_line(const nlohmann::json& summary);

}  // namespace pipeline
