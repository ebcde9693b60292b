#pragma once
// Strict reader of one YAML mapping (private to the scene library: yaml-cpp
// stays out of public headers). Every accessor records the key as known;
// finish() rejects the rest. Messages: "FILE:LINE: key 'a.b': expected ...".
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "scene/vec2.hpp"

namespace scene {

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  std::string describe() const;
  bool contains(double v) const;
};
inline Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
inline Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }

class Section {
 public:
  Section(YAML::Node node, std::string file, std::string path);

  bool has(const std::string& key) const;
  double number(const std::string& key, double def, const Range& r = {});
  std::optional<double> opt_number(const std::string& key, const Range& r = {});
  std::int64_t integer(const std::string& key, std::int64_t def, std::int64_t lo, std::int64_t hi);
  std::optional<std::int64_t> opt_integer(const std::string& key, std::int64_t lo, std::int64_t hi);
  bool boolean(const std::string& key, bool def);
  // true | false | auto (nullopt; also when absent).
  std::optional<bool> boolean_or_auto(const std::string& key);
  std::string string(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed = {});
  std::optional<std::string> opt_string(const std::string& key,
                                        const std::vector<std::string>& allowed = {});
  Vec2 vec2(const std::string& key, Vec2 def);
  std::vector<double> numbers(const std::string& key, const std::vector<double>& def,
                              const Range& r = {});
  std::vector<Vec2> points(const std::string& key);  // required list of [x, y]
  // Sub-mapping (empty if absent; error if not a mapping).
  Section child(const std::string& key);
  // Throws for every key not read. Call once all keys are read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail_node(const YAML::Node& n, const std::string& key,
                              const std::string& what) const;
  const std::string& file() const { return file_; }
  std::string full_key(const std::string& key) const;

 private:
  YAML::Node get(const std::string& key);
  YAML::Node node_;
  std::string file_, path_;
  std::set<std::string> known_;
};

}  // namespace scene
