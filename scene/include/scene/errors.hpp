#pragma once
// Error kinds that map onto the contract's exit codes:
// InputError -> exit 2 (usage, YAML, geometry, missing file),
// RunError   -> exit 1 (a run that failed: diverged, crashed solver).
#include <stdexcept>
#include <string>

namespace scene {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace scene
