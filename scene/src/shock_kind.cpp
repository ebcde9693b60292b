#include "scene/shock_kind.hpp"

namespace scene {

std::string to_string(ShockKind k) {
  switch (k) {
    case ShockKind::attached:
      return "attached";
    case ShockKind::detached:
      return "detached";
    case ShockKind::none:
      return "none";
  }
  return "none";
}

ShockKind shock_kind_from(const std::string& text) {
  if (text == "attached") return ShockKind::attached;
  if (text == "detached") return ShockKind::detached;
  return ShockKind::none;
}

}  // namespace scene
