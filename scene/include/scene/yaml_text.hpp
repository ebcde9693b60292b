#pragma once
// The checks the scene loader makes on YAML text before handing it to a
// parser, for other YAML files (calibration tables, sweeps): printable
// UTF-8, a parser run that terminates (yaml-cpp 0.7 loops for ever on some
// malformed text; it is tried in a time- and memory-limited child), one
// document, no duplicate or non-scalar keys. InputError "ORIGIN[:LINE]: ..."
// otherwise. yaml-cpp stays out of this header.
#include <string>

namespace scene {

void check_yaml_text(const std::string& text, const std::string& origin);

}  // namespace scene
