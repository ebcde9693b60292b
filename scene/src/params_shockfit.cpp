#include "params_parse.hpp"

namespace scene {

ShockfitParams parse_shockfit(Section& s) {
  ShockfitParams p;
  p.stations = static_cast<int>(s.integer("stations", p.stations, 3, 100000));
  p.field = s.string("field", p.field, {"auto", "density", "volume_fraction", "rho", "number_density", "v"});
  p.min_samples = static_cast<int>(s.integer("min_samples", p.min_samples, 0, 1000000000));
  p.noise_factor = s.number("noise_factor", p.noise_factor, positive());
  p.bootstrap = static_cast<int>(s.integer("bootstrap", p.bootstrap, 10, 1000000));
  p.seed = static_cast<std::uint64_t>(s.integer("seed", 1, 0, 1000000000000));
  p.window = s.number("window", p.window, Range{1.0, 1000.0});
  return p;
}

void emit_shockfit(YAML::Emitter& e, const ShockfitParams& p) {
  e << YAML::BeginMap;
  emit_kv(e, "stations", p.stations);
  emit_kv(e, "field", p.field);
  emit_kv(e, "min_samples", p.min_samples);
  emit_kv(e, "noise_factor", p.noise_factor);
  emit_kv(e, "bootstrap", p.bootstrap);
  emit_kv(e, "seed", p.seed);
  emit_kv(e, "window", p.window);
  e << YAML::EndMap;
}

}  // namespace scene
