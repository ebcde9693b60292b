#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "params_parse.hpp"

namespace scene {

namespace {
// Collision counts are converted to 64-bit integers: keep them well inside.
constexpr double kMaxCollisions = 1e18;
// Granular Mach ceiling (see freestream.mach): the inflow speed grows with
// it and so does the event rate; 1e308 overflowed into a hang.
constexpr double kMaxMach = 50.0;
// Warm-up and averaging in flow-through times: beyond this a run is a typo
// that would never finish.
constexpr double kMaxFlowThroughs = 1e6;
// A shock position known to worse than a body length is no prediction: the
// largest explicit precision target (body lengths).
constexpr double kMaxTargetHalfWidth = 1.0;
// Gravity per unit mass, in T/(m d): a thousand times the thermal scale
// already throws every disk onto the floor within one collision time.
constexpr double kMaxGravity = 1e3;
// Elastic impacts below this many thermal speeds: beyond the stream's own
// speed at the Mach ceiling every impact would be elastic, the gas ideal.
constexpr double kMaxImpactSpeed = 100.0;
// `target_half_width`: a half-width in body lengths, `mesh`, `band` or `standoff`.
void parse_precision_target(Section& s, GranularParams& p) {
  const std::optional<std::string> text = s.opt_string("target_half_width");
  if (!text) return;
  if (*text == "mesh") {
    p.target_from_mesh = true;
    return;
  }
  if (*text == "band") {
    p.target_from_band = true;
    return;
  }
  if (*text == "standoff") {
    p.target_from_standoff = true;
    return;
  }
  char* end = nullptr;
  const double v = std::strtod(text->c_str(), &end);
  const Range r{0.0, kMaxTargetHalfWidth, true, false};
  if (text->empty() || end != text->c_str() + text->size() || !r.contains(v))
    s.fail("target_half_width", "expected a half-width in body lengths (" + r.describe() +
                                    ") or 'mesh', 'band' or 'standoff', got '" + *text + "'");
  p.target_half_width = v;
}

}  // namespace

GranularParams parse_granular(Section& s) {
  GranularParams p;
  constexpr auto kMaxI = std::numeric_limits<std::int64_t>::max();
  p.particles = s.opt_integer("particles", 1, kMaxI);
  p.packing_fraction = s.opt_number("packing_fraction", {0.0, 0.9069, true, false});
  p.restitution_given = s.has("restitution");
  p.restitution = s.number("restitution", p.restitution, {0.0, 1.0, true, false});
  p.restitution_wall = s.opt_number("restitution_wall", {0.0, 1.0, true, false});
  p.seed = static_cast<std::uint64_t>(s.integer("seed", 1, 0, kMaxI));
  p.collisions = s.opt_number("collisions", {0.0, kMaxCollisions, true, false});
  p.time = s.opt_number("time", positive());
  p.tc = s.number("tc", p.tc, non_negative());
  p.elastic_impact_speed =
      s.number("elastic_impact_speed", p.elastic_impact_speed, {0.0, kMaxImpactSpeed});
  p.checkpoint_interval = s.opt_number("checkpoint_interval", {0.0, kMaxCollisions, true, false});
  p.gravity = s.vec2("gravity", p.gravity);
  if (std::abs(p.gravity.x) > kMaxGravity || std::abs(p.gravity.y) > kMaxGravity)
    s.fail("gravity", "expected components within +-" + std::to_string(static_cast<int>(kMaxGravity)));
  p.mach = s.opt_number("mach", positive());
  if (p.mach && *p.mach > kMaxMach)
    s.fail("mach", "expected a number in (0, 50], got " + std::to_string(*p.mach));
  p.inflow_packing_fraction =
      s.number("inflow_packing_fraction", p.inflow_packing_fraction, {0.0, 0.6, true, false});
  p.body_diameters = s.opt_number("body_diameters", {2.0, 1e5, false, false});
  p.lattice_nx = static_cast<int>(s.integer("lattice_nx", p.lattice_nx, 2, 100000));
  p.lattice_ny = static_cast<int>(s.integer("lattice_ny", p.lattice_ny, 2, 100000));
  p.warmup = s.opt_number("warmup", {0.0, kMaxFlowThroughs});
  p.averaging_given = s.has("averaging");
  p.averaging = s.number("averaging", p.averaging, {0.0, kMaxFlowThroughs, true, false});
  parse_precision_target(s, p);
  p.cpu_budget = s.opt_number("cpu_budget", positive());
  p.max_averaging =
      s.number("max_averaging", p.max_averaging, {0.0, kMaxFlowThroughs, true, false});
  p.replicas_given = s.has("replicas");
  p.replicas = static_cast<int>(s.integer("replicas", p.replicas, 1, 10000));
  p.snapshots = s.boolean("snapshots", p.snapshots);
  return p;
}

void emit_granular(YAML::Emitter& e, const GranularParams& p) {
  e << YAML::BeginMap;
  emit_opt(e, "particles", p.particles);
  emit_opt(e, "packing_fraction", p.packing_fraction);
  emit_kv(e, "restitution", p.restitution);
  emit_opt(e, "restitution_wall", p.restitution_wall);
  emit_kv(e, "seed", p.seed);
  emit_opt(e, "collisions", p.collisions);
  emit_opt(e, "time", p.time);
  emit_kv(e, "tc", p.tc);
  emit_kv(e, "elastic_impact_speed", p.elastic_impact_speed);
  emit_opt(e, "checkpoint_interval", p.checkpoint_interval);
  emit_vec2(e, "gravity", p.gravity);
  emit_opt(e, "mach", p.mach);
  emit_kv(e, "inflow_packing_fraction", p.inflow_packing_fraction);
  emit_opt(e, "body_diameters", p.body_diameters);
  emit_kv(e, "lattice_nx", p.lattice_nx);
  emit_kv(e, "lattice_ny", p.lattice_ny);
  emit_opt(e, "warmup", p.warmup);
  emit_kv(e, "averaging", p.averaging);
  if (p.target_from_mesh)
    emit_kv(e, "target_half_width", "mesh");
  else if (p.target_from_band)
    emit_kv(e, "target_half_width", "band");
  else if (p.target_from_standoff)
    emit_kv(e, "target_half_width", "standoff");
  else
    emit_opt(e, "target_half_width", p.target_half_width);
  emit_opt(e, "cpu_budget", p.cpu_budget);
  emit_kv(e, "max_averaging", p.max_averaging);
  emit_kv(e, "replicas", p.replicas);
  emit_kv(e, "snapshots", p.snapshots);
  e << YAML::EndMap;
}

}  // namespace scene
