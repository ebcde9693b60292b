#include "params_parse.hpp"

namespace scene {

MeshParams parse_mesh(Section& s) {
  MeshParams p;
  p.sizes_default = !s.has("h_min") && !s.has("h_max");
  p.h_min = s.number("h_min", p.h_min, positive());
  p.h_max = s.number("h_max", p.h_max, positive());
  p.band_width = s.opt_number("band_width", positive());
  p.growth = s.number("growth", p.growth, {1.0, 10.0, true, false});
  p.target_cells = s.opt_number("target_cells", {10.0, 1e9, false, false});
  p.recombine = s.boolean("recombine", p.recombine);
  p.h_body = s.opt_number("h_body", positive());
  p.h_uniform = s.opt_number("h_uniform", positive());
  p.algorithm = s.string("algorithm", p.algorithm, {"delaunay", "frontal"});
  p.smoothing = static_cast<int>(s.integer("smoothing", p.smoothing, 0, 100));
  p.anisotropy = s.opt_number("anisotropy", {1.0, 50.0, false, false});
  p.extend_shock = s.boolean("extend_shock", p.extend_shock);
  if (p.h_min > p.h_max) s.fail("h_min", "must not exceed h_max");
  if (p.h_body && (*p.h_body < p.h_min || *p.h_body > p.h_max))
    s.fail("h_body", "must lie between h_min and h_max");
  return p;
}

void emit_mesh(YAML::Emitter& e, const MeshParams& p) {
  e << YAML::BeginMap;
  emit_kv(e, "h_min", p.h_min);
  emit_kv(e, "h_max", p.h_max);
  emit_opt(e, "band_width", p.band_width);
  emit_kv(e, "growth", p.growth);
  emit_opt(e, "target_cells", p.target_cells);
  emit_kv(e, "recombine", p.recombine);
  emit_opt(e, "h_body", p.h_body);
  emit_opt(e, "h_uniform", p.h_uniform);
  emit_kv(e, "algorithm", p.algorithm);
  emit_kv(e, "smoothing", p.smoothing);
  emit_opt(e, "anisotropy", p.anisotropy);
  if (!p.extend_shock) emit_kv(e, "extend_shock", p.extend_shock);
  e << YAML::EndMap;
}

}  // namespace scene
