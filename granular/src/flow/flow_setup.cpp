#include "granular/flow_setup.hpp"

#include <cmath>
#include <string>

#include "granular/particle_budget.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/units.hpp"

namespace granular {

namespace {

// Disk area in units of d^2 (radius 1/2).
using scene::kDiskArea;
// Sub-cells per side when measuring the fluid (non-body) area of the domain.
constexpr int kAreaSamples = 256;
// Room added upstream of (and above) the scene domain for blunt bodies, in
// body half-heights: the granular gas (gamma = 2, dense) compresses less
// than air, so its bow shock stands 2-3 times further off than Billig's
// air correlation that sizes the scene domain (disc M4: ~1.2 radii instead
// of 0.5), which would put the shock on the inflow boundary.
constexpr double kBluntUpstreamMargin = 1.0;
constexpr double kBluntSideMargin = 0.5;
// The granular gas is gamma = 2 in the dilute limit (attachment test).
constexpr double kGranularGamma = 2.0;
// Closest packing of disks: an inflow at or above it cannot exist; beyond
// ~0.7 the fluid crystallises and Henderson's Z is meaningless.
constexpr double kMaxInflowPacking = 0.6;

double fluid_area_scene(const scene::BodyGeometry& g, const scene::Domain& d) {
  const double hx = d.width() / kAreaSamples, hy = d.height() / kAreaSamples;
  int inside = 0;
  for (int j = 0; j < kAreaSamples; ++j)
    for (int i = 0; i < kAreaSamples; ++i)
      if (scene::point_in_body(g, {d.xmin + (i + 0.5) * hx, d.ymin + (j + 0.5) * hy})) ++inside;
  return d.width() * d.height() * (1.0 - static_cast<double>(inside) / (kAreaSamples * kAreaSamples));
}

}  // namespace

double sound_speed(double nu, double temperature) {
  const double z = henderson_z(nu);
  const double dz = henderson_dz(nu);
  return std::sqrt(temperature * (z + nu * dz + z * z));
}

double granular_mach(const scene::Scene& s) { return s.granular.mach.value_or(s.freestream.mach); }

FlowSetup make_flow_setup(const scene::Scene& s) {
  if (!s.body) throw scene::InputError(s.source_file + ": granular flow needs a body: section");
  const scene::GranularParams& p = s.granular;
  const std::string where = s.source_file + ": granular: ";
  FlowSetup f;
  f.body = scene::make_body(*s.body);
  f.domain = scene::scene_domain(s);  // InputError when the body touches an edge
  // Gravity across the stream breaks the mirror symmetry: model the full body.
  if (f.domain.symmetric && p.gravity.y != 0.0) {
    f.domain.ymin = -f.domain.ymax;
    f.domain.symmetric = false;
  }
  f.mach = granular_mach(s);
  if (!(f.mach > 1.0))
    throw scene::InputError(where + "key 'mach': the granular Mach number must exceed 1 for a shock, got " +
                            std::to_string(f.mach));
  // `packing_fraction` (the box key) is accepted for flows as the inflow value.
  f.packing_fraction = p.packing_fraction.value_or(p.inflow_packing_fraction);
  if (!(f.packing_fraction > 0.0 && f.packing_fraction <= kMaxInflowPacking))
    throw scene::InputError(where + "key 'inflow_packing_fraction': expected a value in (0, 0.6], got " +
                            std::to_string(f.packing_fraction));
  f.number_density = f.packing_fraction / kDiskArea;
  f.sound_speed = sound_speed(f.packing_fraction, 1.0);

  f.sim_domain = f.domain;
  const bool attached_wedge =
      scene::attached_shock_beta(*s.body, f.mach, kGranularGamma).has_value();
  if (!attached_wedge && !s.domain_override) {
    double ylo = 0, yhi = 0;
    for (const scene::Vec2 q : f.body.polyline) {
      ylo = std::min(ylo, q.y);
      yhi = std::max(yhi, q.y);
    }
    const double h = f.domain.symmetric ? yhi : 0.5 * (yhi - ylo);
    f.sim_domain.xmin -= kBluntUpstreamMargin * h;
    f.sim_domain.ymax += kBluntSideMargin * h;
    if (!f.sim_domain.symmetric) f.sim_domain.ymin -= kBluntSideMargin * h;
  }
  const double fluid_scene = fluid_area_scene(f.body, f.domain);
  // Scale: body_diameters when given, else `particles` (disks in the domain
  // at the inflow density), else the default particle count.
  if (p.body_diameters) {
    f.scale = *p.body_diameters / f.body.length;
  } else {
    const double particles = p.particles ? static_cast<double>(*p.particles) : scene::kDefaultFlowParticles;
    f.scale = std::sqrt(particles / (f.number_density * fluid_scene));
  }
  f.fluid_area = fluid_scene * f.scale * f.scale;
  f.expected_particles = f.number_density * f.fluid_area;
  {
    // The simulated rectangle (larger than the domain for blunt bodies) is
    // what the engine fills; each replica thread holds its own engine.
    const double sim_area = f.sim_domain.width() * f.sim_domain.height() * f.scale * f.scale;
    check_particle_budget(f.number_density * sim_area, 1,
                          where + (p.body_diameters ? "key 'body_diameters': " : "key 'particles': "));
  }

  FlowConfig& c = f.config;
  c.xmin = f.sim_domain.xmin * f.scale;
  c.xmax = f.sim_domain.xmax * f.scale;
  c.ymin = f.sim_domain.ymin * f.scale;
  c.ymax = f.sim_domain.ymax * f.scale;
  c.symmetric = f.sim_domain.symmetric;
  c.body_chains = body_chains(f.body, f.sim_domain);
  for (auto& chain : c.body_chains)
    for (scene::Vec2& q : chain) q = to_engine(f, q);
  c.inflow_speed = f.mach * f.sound_speed;
  c.temperature = 1.0;
  c.packing_fraction = f.packing_fraction;
  c.radius = 0.5;
  c.mass = 1.0;
  c.restitution = p.restitution;
  c.restitution_wall = p.restitution_wall.value_or(p.restitution);
  c.tc = p.tc;
  c.elastic_below = p.elastic_impact_speed;
  c.gravity = p.gravity;
  c.seed = p.seed;
  c.prefill = true;
  f.flow_through_time = (c.xmax - c.xmin) / c.inflow_speed;
  return f;
}

nlohmann::json describe(const FlowSetup& f) {
  const FlowConfig& c = f.config;
  return {
      {"mach", f.mach},
      {"inflow_speed", c.inflow_speed},
      {"sound_speed", f.sound_speed},
      {"inflow_packing_fraction", f.packing_fraction},
      {"inflow_number_density", f.number_density},
      {"inflow_pressure", f.number_density * henderson_z(f.packing_fraction)},
      {"body_diameters", f.body.length * f.scale},
      {"diameters_per_scene_unit", f.scale},
      {"domain_diameters", {c.xmin, c.xmax, c.ymin, c.ymax}},
      {"domain_scene", {f.domain.xmin, f.domain.xmax, f.domain.ymin, f.domain.ymax}},
      {"simulated_domain_scene",
       {f.sim_domain.xmin, f.sim_domain.xmax, f.sim_domain.ymin, f.sim_domain.ymax}},
      {"symmetric", c.symmetric},
      {"expected_particles", f.expected_particles},
      {"flow_through_time", f.flow_through_time},
      {"restitution", c.restitution},
      {"restitution_wall", c.restitution_wall},
      {"elastic_impact_speed", c.elastic_below},
      {"gravity", {c.gravity.x, c.gravity.y}},
  };
}

}  // namespace granular
