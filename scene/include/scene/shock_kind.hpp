#pragma once
// What a shock locator or predictor found: a shock attached to the body (an
// angle), one standing off it (a standoff), or none. Text only in files
// (summary.json's "shock" key).
#include <string>

namespace scene {

enum class ShockKind { attached, detached, none };

// "attached" | "detached" | "none".
std::string to_string(ShockKind k);
// The inverse of to_string; any other text (a missing key) is none.
ShockKind shock_kind_from(const std::string& text);

}  // namespace scene
