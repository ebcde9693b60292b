#pragma once
// Per-stage section parsers and emitters (private). Each stage's owner keeps
// its own params_<stage>.cpp.
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "scene/stage_params.hpp"
#include "section.hpp"

namespace scene {

GranularParams parse_granular(Section& s);
ShockfitParams parse_shockfit(Section& s);
MeshParams parse_mesh(Section& s);
CfdParams parse_cfd(Section& s);
PipelineParams parse_pipeline(Section& s);

void emit_granular(YAML::Emitter& e, const GranularParams& p);
void emit_shockfit(YAML::Emitter& e, const ShockfitParams& p);
void emit_mesh(YAML::Emitter& e, const MeshParams& p);
void emit_cfd(YAML::Emitter& e, const CfdParams& p);
void emit_pipeline(YAML::Emitter& e, const PipelineParams& p);

// Helpers for emitters. A double is written as the shortest decimal that
// reads back to the same double: the values people write stay as written
// (1.4), and computed ones (a domain edge) reproduce the run bit for bit
// when the resolved scene is read again.
template <class T>
void emit_value(YAML::Emitter& e, const T& v) {
  if constexpr (std::is_same_v<T, double>) {
    if (std::isfinite(v)) {
      char buf[32];
      const auto r = std::to_chars(buf, buf + sizeof buf, v);
      e << std::string(buf, r.ptr);
      return;
    }
  }
  e << v;
}
template <class T>
void emit_kv(YAML::Emitter& e, const char* k, const T& v) {
  e << YAML::Key << k << YAML::Value;
  emit_value(e, v);
}
template <class T>
void emit_opt(YAML::Emitter& e, const char* k, const std::optional<T>& v) {
  e << YAML::Key << k << YAML::Value;
  if (v)
    emit_value(e, *v);
  else
    e << YAML::Null;
}
inline void emit_pair(YAML::Emitter& e, Vec2 v) {
  e << YAML::Flow << YAML::BeginSeq;
  emit_value(e, v.x);
  emit_value(e, v.y);
  e << YAML::EndSeq;
}
inline void emit_vec2(YAML::Emitter& e, const char* k, Vec2 v) {
  e << YAML::Key << k << YAML::Value;
  emit_pair(e, v);
}
inline void emit_seq(YAML::Emitter& e, const char* k, const std::vector<double>& v) {
  e << YAML::Key << k << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double x : v) emit_value(e, x);
  e << YAML::EndSeq;
}

}  // namespace scene
