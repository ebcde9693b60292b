#pragma once
// Reading numbers back from the stages' summaries and writing them into
// tables: one rule for "missing" (NaN, shown as n/a) across the pipeline.
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "scene/units.hpp"

namespace pipeline {

// j[key] when it is a number, else NaN (a missing or null value).
inline double number_or_nan(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>()
                                                                : scene::kNaN;
}

// v, or null when it is not finite (JSON has no NaN).
inline nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// `prec` significant digits; "n/a" for what is not finite.
inline std::string format_number(double v, int prec = 3) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream os;
  os.precision(prec);
  os << v;
  return os.str();
}

// "3.2x (2.1-4.9)" from a {value, ci_low, ci_high} object; an unbounded
// upper end (written as null) reads "inf".
inline std::string speedup_text(const nlohmann::json& i) {
  const double v = number_or_nan(i, "value");
  if (!std::isfinite(v)) return "n/a";
  const std::string hi = i.contains("ci_high") && i["ci_high"].is_null()
                             ? "inf"
                             : format_number(number_or_nan(i, "ci_high"));
  return format_number(v) + "x (" + format_number(number_or_nan(i, "ci_low")) + "-" + hi + ")";
}

}  // namespace pipeline
