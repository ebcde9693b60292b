// Where a CFD engineer would put the band without any simulation: the
// theta-beta-Mach shock line on attached wedges (exact for the inviscid
// gas), Billig's cylinder shock shape elsewhere (an empirical fit, and for
// bodies that are not circular cylinders an approximation with the
// radius of scene::correlation_nose_radius).
#include "pipeline/predictors.hpp"

#include <chrono>
#include <cmath>

#include "pipeline/stage_cache.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kDeg;
// Billig's fits reproduce measured cylinder standoffs within a few percent;
// the band takes +-10% of the standoff on a cylinder, and +-30% on bodies
// whose nose is only approximated by a cylinder.
constexpr double kBilligCylinderRel = 0.10;
constexpr double kBilligApproximateRel = 0.30;
}  // namespace

CorrelationShock correlation_shock(const scene::Scene& s) {
  CorrelationShock c;
  if (const auto beta = scene::attached_shock_beta(s)) {
    c.kind = scene::ShockKind::attached;
    c.angle_deg = *beta / kDeg;
    c.curve = apex_ray(scene::scene_domain(s), scene::make_body(*s.body).nose, c.angle_deg, 0.0);
    return c;
  }
  c.kind = scene::ShockKind::detached;
  c.exact_shape = scene::correlation_is_exact_shape(*s.body);
  c.relative_half_width = c.exact_shape ? kBilligCylinderRel : kBilligApproximateRel;
  c.curve = billig_bow_shock(s, c.relative_half_width);
  return c;
}

Prediction CorrelationPredictor::predict(const PredictContext& cx) const {
  const auto t0 = std::chrono::steady_clock::now();
  const scene::CpuStopwatch cpu;
  const scene::Scene& s = cx.scene;
  Prediction p;
  p.predictor = name();
  const CorrelationShock c = correlation_shock(s);
  const ShockCurve& curve = c.curve;
  p.kind = c.kind;
  if (c.kind == scene::ShockKind::attached) {
    p.shock_angle_deg = c.angle_deg;
    p.shock_angle_ci_deg = 0.0;
    p.details = {{"correlation", "theta-beta-Mach relation (exact for the inviscid gas)"}};
  } else {
    p.standoff = billig_standoff(s) / scene::body_length(*s.body);
    p.standoff_ci = c.relative_half_width * p.standoff;
    p.details = {{"correlation",
                  c.exact_shape ? "Billig (1967) cylinder shock shape"
                                : "Billig (1967) cylinder shock shape with the body's half frontal "
                                  "height as nose radius (an approximation)"},
                 {"nose_radius", scene::correlation_nose_radius(*s.body)},
                 {"relative_half_width", c.relative_half_width}};
  }
  p.curve = curve.points;
  p.half_width = curve.half_width;
  scene::make_dirs(cx.out_dir);
  p.shock_csv = cx.out_dir + "/shock.csv";
  write_shock_curve(p.shock_csv, p.curve, p.half_width);
  p.fingerprint = fingerprint({"correlation", scene::section_yaml(s, "body"), scene::section_yaml(s, "freestream"),
                               scene::section_yaml(s, "domain")});
  p.cpu_seconds = cpu.seconds();
  p.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return p;
}

}  // namespace pipeline
