#include "section.hpp"

#include <cmath>
#include <sstream>

#include "scene/errors.hpp"

namespace scene {

static std::string fmt_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string Range::describe() const {
  std::ostringstream os;
  const bool lo_inf = std::isinf(lo), hi_inf = std::isinf(hi);
  if (lo_inf && hi_inf) return "any finite number";
  if (hi_inf) return (lo_open ? "a number > " : "a number >= ") + fmt_number(lo);
  if (lo_inf) return (hi_open ? "a number < " : "a number <= ") + fmt_number(hi);
  os << "a number in " << (lo_open ? "(" : "[") << fmt_number(lo) << ", " << fmt_number(hi)
     << (hi_open ? ")" : "]");
  return os.str();
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

Section::Section(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

std::string Section::full_key(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void Section::fail(const std::string& key, const std::string& what) const {
  std::ostringstream os;
  os << file_;
  if (node_ && node_.IsDefined() && !node_.IsNull() && node_.Mark().line >= 0)
    os << ":" << node_.Mark().line + 1;
  os << ": key '" << full_key(key) << "': " << what;
  throw InputError(os.str());
}

void Section::fail_node(const YAML::Node& n, const std::string& key,
                        const std::string& what) const {
  std::ostringstream os;
  os << file_;
  if (n.IsDefined() && n.Mark().line >= 0) os << ":" << n.Mark().line + 1;
  os << ": key '" << full_key(key) << "': " << what;
  throw InputError(os.str());
}

bool Section::has(const std::string& key) const {
  return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
}

YAML::Node Section::get(const std::string& key) {
  known_.insert(key);
  if (!node_ || !node_.IsMap()) return YAML::Node();
  YAML::Node n = node_[key];
  if (!n || n.IsNull()) return YAML::Node();
  return n;
}

static bool absent(const YAML::Node& n) { return !n.IsDefined() || n.IsNull(); }

static std::string scalar_text(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "nothing";
}

std::optional<double> Section::opt_number(const std::string& key, const Range& r) {
  const YAML::Node n = get(key);
  if (absent(n)) return std::nullopt;
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v))
    fail_node(n, key, "expected " + r.describe() + ", got " + scalar_text(n));
  if (!r.contains(v)) fail_node(n, key, "expected " + r.describe() + ", got " + n.Scalar());
  return v;
}

double Section::number(const std::string& key, double def, const Range& r) {
  return opt_number(key, r).value_or(def);
}

std::optional<std::int64_t> Section::opt_integer(const std::string& key, std::int64_t lo,
                                                 std::int64_t hi) {
  const YAML::Node n = get(key);
  if (absent(n)) return std::nullopt;
  const std::string want =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  double d = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, d) || std::floor(d) != d)
    fail_node(n, key, "expected " + want + ", got " + scalar_text(n));
  // 2^63 rounds to the double of INT64_MAX, so a plain d > hi lets it through
  // and the cast below is then undefined: compare against 2^63 itself.
  constexpr double kTwoTo63 = 9223372036854775808.0;
  if (!(d < kTwoTo63) || !(d >= -kTwoTo63) || d < static_cast<double>(lo) ||
      d > static_cast<double>(hi) || static_cast<std::int64_t>(d) > hi)
    fail_node(n, key, "expected " + want + ", got " + n.Scalar());
  return static_cast<std::int64_t>(d);
}

std::int64_t Section::integer(const std::string& key, std::int64_t def, std::int64_t lo,
                              std::int64_t hi) {
  return opt_integer(key, lo, hi).value_or(def);
}

bool Section::boolean(const std::string& key, bool def) {
  const YAML::Node n = get(key);
  if (absent(n)) return def;
  bool b = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, b))
    fail_node(n, key, "expected true or false, got " + scalar_text(n));
  return b;
}

std::optional<bool> Section::boolean_or_auto(const std::string& key) {
  const YAML::Node n = get(key);
  if (absent(n)) return std::nullopt;
  if (n.IsScalar() && n.Scalar() == "auto") return std::nullopt;
  bool b = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, b))
    fail_node(n, key, "expected true, false or auto, got " + scalar_text(n));
  return b;
}

std::optional<std::string> Section::opt_string(const std::string& key,
                                               const std::vector<std::string>& allowed) {
  const YAML::Node n = get(key);
  if (absent(n)) return std::nullopt;
  if (!n.IsScalar()) fail_node(n, key, "expected a string, got " + scalar_text(n));
  const std::string v = n.Scalar();
  if (!allowed.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& a : allowed) {
      ok = ok || a == v;
      list += (list.empty() ? "" : " | ") + a;
    }
    if (!ok) fail_node(n, key, "expected one of " + list + ", got '" + v + "'");
  }
  return v;
}

std::string Section::string(const std::string& key, const std::string& def,
                            const std::vector<std::string>& allowed) {
  return opt_string(key, allowed).value_or(def);
}

static bool decode_point(const YAML::Node& n, Vec2& p) {
  if (!n.IsSequence() || n.size() != 2) return false;
  return n[0].IsScalar() && n[1].IsScalar() && YAML::convert<double>::decode(n[0], p.x) &&
         YAML::convert<double>::decode(n[1], p.y) && std::isfinite(p.x) && std::isfinite(p.y);
}

Vec2 Section::vec2(const std::string& key, Vec2 def) {
  const YAML::Node n = get(key);
  if (absent(n)) return def;
  Vec2 p;
  if (!decode_point(n, p)) fail_node(n, key, "expected [x, y] with two finite numbers");
  return p;
}

std::vector<double> Section::numbers(const std::string& key, const std::vector<double>& def,
                                     const Range& r) {
  const YAML::Node n = get(key);
  if (absent(n)) return def;
  if (!n.IsSequence() || n.size() == 0)
    fail_node(n, key, "expected a non-empty list of numbers, got " + scalar_text(n));
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], v) || !r.contains(v))
      fail_node(n[i], key, "item " + std::to_string(i) + ": expected " + r.describe());
    out.push_back(v);
  }
  return out;
}

std::vector<Vec2> Section::points(const std::string& key) {
  const YAML::Node n = get(key);
  if (absent(n)) fail(key, "required: a list of [x, y] points");
  if (!n.IsSequence()) fail_node(n, key, "expected a list of [x, y] points, got " + scalar_text(n));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    Vec2 p;
    if (!decode_point(n[i], p))
      fail_node(n[i], key, "point " + std::to_string(i) + ": expected [x, y] with two finite numbers");
    out.push_back(p);
  }
  return out;
}

Section Section::child(const std::string& key) {
  const YAML::Node n = get(key);
  if (!absent(n) && !n.IsMap()) fail_node(n, key, "expected a mapping, got " + scalar_text(n));
  return Section(absent(n) ? YAML::Node() : n, file_, full_key(key));
}

void Section::finish() const {
  if (!node_ || !node_.IsMap()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string k = it->first.as<std::string>();
    if (!known_.count(k)) {
      std::string list;
      for (const auto& a : known_) list += (list.empty() ? "" : ", ") + a;
      fail_node(it->first, k, "unknown key (known here: " + list + ")");
    }
  }
}

}  // namespace scene
