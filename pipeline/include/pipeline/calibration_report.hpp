#pragma once
// The out-of-sample summary and the markdown table of `pipeline calibrate`,
// both computed from its calibration.json object.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "pipeline/restitution_local.hpp"

namespace pipeline {

// RMS and max |error| of the granular angle against the gas angle, over the
// leave-one-out runs and over the case studies that are not training points.
nlohmann::json out_of_sample_summary(const nlohmann::json& calibration);

// The chosen model's local correction as calibration.json records it
// (null when the calibration kept none).
nlohmann::json local_correction_json(const std::optional<LocalCorrection>& c);

// Method line, model table, leave-one-out table and case-study table, ready
// to paste into docs (docs/calibration.md).
std::string calibration_markdown(const nlohmann::json& calibration);

}  // namespace pipeline
