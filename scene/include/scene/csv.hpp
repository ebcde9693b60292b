#pragma once
// One line of a CSV file (shock.csv, the CFD stage's history.csv) split into
// its fields.
#include <string>
#include <vector>

namespace scene {

// Fields: split at commas, trimmed of spaces and of surrounding quotes; a
// trailing comma ends in an empty field.
std::vector<std::string> split_csv(const std::string& line);

}  // namespace scene
