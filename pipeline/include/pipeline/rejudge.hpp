#pragma once
// `pipeline verdict RUNDIR`: the verdict recomputed from a finished run's
// recorded grids (summary.json's runs[]) with the current method, without
// running anything again. Two recorded runs of the same scene judged by the
// same method show whether the verdict reproduces.
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/verdict.hpp"

namespace pipeline {

// The verdict of the runs recorded in `summary_path` (InputError naming the
// file and key when a run lacks what the verdict needs).
Verdict rejudge_summary(const std::string& summary_path);

// verdict.json beside the summary: the verdict's details, the scene name
// and the line `pipeline run` prints; returns that line.
std::string write_rejudged(const std::string& run_dir);

}  // namespace pipeline
