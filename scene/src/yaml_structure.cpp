#include "yaml_structure.hpp"

#include <set>
#include <vector>

#include "scene/errors.hpp"

namespace scene {

namespace {

// A hostile file can nest [[[[...]]]] deep enough to exhaust the stack of a
// recursive walk; no scene is deeper than a handful of levels.
constexpr int kMaxDepth = 64;

std::string at(const std::string& origin, const YAML::Mark& m) {
  return m.line >= 0 ? origin + ":" + std::to_string(m.line + 1) : origin;
}

void check_node(const YAML::Node& n, const std::string& origin, const std::string& path,
                int depth) {
  if (depth > kMaxDepth)
    throw InputError(at(origin, n.Mark()) + ": YAML nested deeper than " +
                     std::to_string(kMaxDepth) + " levels");
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      check_node(n[i], origin, path + "[" + std::to_string(i) + "]", depth + 1);
    return;
  }
  if (!n.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : n) {
    const YAML::Node key = kv.first;
    if (!key.IsScalar())
      throw InputError(at(origin, key.Mark()) + ": " +
                       (path.empty() ? "top level" : "key '" + path + "'") +
                       ": expected plain scalar keys, got a " +
                       (key.IsMap()        ? "mapping"
                        : key.IsSequence() ? "list"
                                           : "null") +
                       " as a key");
    const std::string k = key.Scalar();
    const std::string full = path.empty() ? k : path + "." + k;
    if (!seen.insert(k).second)
      throw InputError(at(origin, key.Mark()) + ": key '" + full +
                       "': duplicate key (each key may appear once)");
    check_node(kv.second, origin, full, depth + 1);
  }
}

}  // namespace

YAML::Node load_single_document(const std::string& text, const std::string& origin) {
  std::vector<YAML::Node> docs;
  try {
    docs = YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    throw InputError(origin + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  if (docs.size() > 1)
    throw InputError(at(origin, docs[1].Mark()) + ": expected one YAML document, found " +
                     std::to_string(docs.size()) + " (a second document starts here)");
  const YAML::Node root = docs.empty() ? YAML::Node() : docs.front();
  check_node(root, origin, "", 0);
  return root;
}

}  // namespace scene
