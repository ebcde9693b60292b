#pragma once
// history.csv, the case monitor's record of a run (one row per written
// time; docs/cfd_cases.md, "Steady state"), read back by later stages.
#include <string>

namespace cfd {

// The last finite value in `column` of CASE_DIR/history.csv: where the run
// stopped. InputError naming the file for a missing or unreadable file, a
// missing column or no finite value in it.
double last_history_value(const std::string& case_dir, const std::string& column);

}  // namespace cfd
