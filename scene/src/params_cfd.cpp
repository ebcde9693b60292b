#include "params_parse.hpp"

namespace scene {

namespace {
// Flow-through times: end_time beyond this is a typo that never finishes.
constexpr double kMaxEndTime = 1e4;
// Written times per run: each is a directory of fields on disk.
constexpr double kMaxWrites = 1e4;
}  // namespace

CfdParams parse_cfd(Section& s) {
  CfdParams p;
  p.max_co = s.number("max_co", p.max_co, {0.0, 5.0, true, false});
  p.end_time = s.number("end_time", p.end_time, {0.0, kMaxEndTime, true, false});
  p.write_interval = s.number("write_interval", p.write_interval, positive());
  p.steady_tol = s.number("steady_tol", p.steady_tol, positive());
  p.force_tol = s.number("force_tol", p.force_tol, positive());
  p.local_time_stepping = s.boolean_or_auto("local_time_stepping");
  p.np = static_cast<int>(s.integer("np", p.np, 1, 4096));
  p.flux_scheme = s.string("flux_scheme", p.flux_scheme, {"auto", "Kurganov", "Tadmor"});
  p.limiter = s.string("limiter", p.limiter, {"auto", "vanLeer", "Minmod"});
  p.min_time = s.number("min_time", p.min_time, non_negative());
  p.steady_checks = static_cast<int>(s.integer("steady_checks", p.steady_checks, 1, 1000));
  p.start = s.string("start", p.start, {"auto", "freestream", "rest", "rest_behind_base"});
  p.fallback = s.boolean("fallback", p.fallback);
  if (p.write_interval > p.end_time) s.fail("write_interval", "must not exceed end_time");
  if (p.end_time / p.write_interval > kMaxWrites)
    s.fail("write_interval", "end_time / write_interval must not exceed " + std::to_string(static_cast<int>(kMaxWrites)) +
                                 " written times, got " + std::to_string(p.end_time / p.write_interval));
  return p;
}

void emit_cfd(YAML::Emitter& e, const CfdParams& p) {
  e << YAML::BeginMap;
  emit_kv(e, "max_co", p.max_co);
  emit_kv(e, "end_time", p.end_time);
  emit_kv(e, "write_interval", p.write_interval);
  emit_kv(e, "steady_tol", p.steady_tol);
  emit_kv(e, "force_tol", p.force_tol);
  if (p.local_time_stepping)
    emit_kv(e, "local_time_stepping", *p.local_time_stepping);
  else
    emit_kv(e, "local_time_stepping", std::string("auto"));
  emit_kv(e, "np", p.np);
  emit_kv(e, "flux_scheme", p.flux_scheme);
  emit_kv(e, "limiter", p.limiter);
  emit_kv(e, "min_time", p.min_time);
  emit_kv(e, "steady_checks", p.steady_checks);
  emit_kv(e, "start", p.start);
  emit_kv(e, "fallback", p.fallback);
  e << YAML::EndMap;
}

}  // namespace scene
