#pragma once
// Per-stage result cache: DIR/<stage>/.stage.json records the fingerprint of
// what the stage depended on (the scene sections it reads, its inputs'
// fingerprints, the code version). A stage is skipped when its record matches;
// the record is written last, so a stage interrupted midway reruns.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pipeline {

// FNV-1a 64-bit over the code version and the parts, as 16 hex digits.
std::string fingerprint(const std::vector<std::string>& parts);

class StageCache {
 public:
  explicit StageCache(std::string root) : root_(std::move(root)) {}
  std::string dir(const std::string& stage) const { return root_ + "/" + stage; }
  // True when the stage finished before with this fingerprint.
  bool fresh(const std::string& stage, const std::string& fp) const;
  // The record's `result` object (empty object if none).
  nlohmann::json result(const std::string& stage) const;
  void mark_done(const std::string& stage, const std::string& fp, const nlohmann::json& result) const;
  void invalidate(const std::string& stage) const;

 private:
  std::string root_;
};

}  // namespace pipeline
