#pragma once
// `pipeline verdict RUNDIR`: the verdict recomputed from a finished run's
// recorded grids (summary.json's runs[]) with the current method, without
// running anything again. Two recorded runs of the same scene judged by the
// same method show whether the verdict reproduces.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/verdict.hpp"

namespace pipeline {

// A `pipeline run` summary read back (InputError naming the file: `path:
// <when_missing>` when it is absent, "not JSON" when malformed).
constexpr const char* kNoRunSummary = "no such run summary";
nlohmann::json read_run_summary(const std::string& path, const std::string& when_missing);

// The verdict of the runs recorded in `summary_path` (InputError naming the
// file and key when a run lacks what the verdict needs).
Verdict rejudge_summary(const std::string& summary_path);

// The runs of one family ("uniform", "clustered", "clustered-adapt", ...)
// recorded in a `pipeline run` summary read from `path` (named in errors).
std::vector<VerdictRun> recorded_family(const nlohmann::json& summary, const std::string& path,
                                        const std::string& family);

// verdict.json beside the summary: the verdict's details, the scene name,
// and the line `pipeline run` prints; returns that line. With `remeasure`,
// every grid's errors are measured again from its CFD case
// (RUNDIR/cfd/<grid>) by the current error measures, the primary error is
// chosen for the resolved scene (RUNDIR/scene.resolved.yaml) as a new run
// would, and the new errors are listed; a case that cannot be read leaves
// that grid out of the fit.
std::string write_rejudged(const std::string& run_dir, bool remeasure = false);

}  // namespace pipeline
