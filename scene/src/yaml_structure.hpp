#pragma once
// Structural checks on a YAML text before any key is read (private to the
// scene library). yaml-cpp accepts several things a scene must not hold: a
// second document (silently ignored by YAML::Load), duplicate keys (the
// first one wins, so an edit further down is silently lost) and non-scalar
// keys (which later fail with a conversion error instead of a clear line).
#include <yaml-cpp/yaml.h>

#include <string>

namespace scene {

// Parses exactly one YAML document from `text`. Throws InputError
// "ORIGIN:LINE: ..." on malformed YAML, more than one document, a duplicate
// key or a key that is not a plain scalar, anywhere in the tree.
YAML::Node load_single_document(const std::string& text, const std::string& origin);

}  // namespace scene
