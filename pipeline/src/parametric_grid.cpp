// The parametric study's grids and the scene of each point.
#include <cmath>
#include <cstdio>

#include "pipeline/parametric.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {

using scene::kDeg;
// Deflections up to the gamma = 1.4 detachment angle, plus the first one past
// it so that a panel shows the granular shock detaching.
std::vector<double> thetas_to_detachment(double mach, const std::vector<double>& candidates) {
  std::vector<double> out;
  const double limit = scene::max_deflection(mach, 1.4) / kDeg;
  for (const double t : candidates) {
    out.push_back(t);
    if (t > limit) break;
  }
  return out;
}

ParametricPoint wedge(double mach, double theta, double e) {
  ParametricPoint p;
  p.body = "wedge";
  p.mach = mach;
  p.granular_mach = mach;
  p.theta_deg = theta;
  p.restitution = e;
  return p;
}

ParametricPoint disc(double mach, double radius_d, double e) {
  ParametricPoint p;
  p.body = "disc";
  p.mach = mach;
  p.granular_mach = mach;
  p.radius_d = radius_d;
  p.restitution = e;
  return p;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::vector<ParametricPanel> parametric_panels(ParametricGrid grid) {
  const bool quick = grid == ParametricGrid::quick;
  const std::vector<double> thetas =
      quick ? std::vector<double>{10, 20} : std::vector<double>{5, 10, 15, 20, 25, 30};
  const std::vector<double> thetas_m3 =
      quick ? std::vector<double>{10, 20} : std::vector<double>{5, 10, 15, 20, 25};
  const std::vector<double> radii = quick ? std::vector<double>{50} : std::vector<double>{50, 70};
  std::vector<ParametricPanel> panels;

  ParametricPanel wm{"wedge_mach",
                     "Wedge: shock angle against deflection, several Mach numbers (e = 1)",
                     "theta_beta",
                     {}};
  for (const double m : quick ? std::vector<double>{3} : std::vector<double>{2, 3, 5})
    for (const double t : thetas_to_detachment(m, thetas)) wm.points.push_back(wedge(m, t, 1.0));
  panels.push_back(wm);

  ParametricPanel we{"wedge_restitution",
                     "Wedge at M = 3: shock angle against deflection, several restitutions",
                     "theta_beta",
                     {}};
  for (const double e :
       quick ? std::vector<double>{1.0, 0.95} : std::vector<double>{1.0, 0.99, 0.97, 0.95, 0.9})
    for (const double t : thetas_m3) we.points.push_back(wedge(3, t, e));
  panels.push_back(we);

  if (!quick) {
    ParametricPanel wt{"wedge_temperature",
                       "Wedge, gas M = 3: shock angle against deflection, several inflow "
                       "temperatures (granular Mach)",
                       "theta_beta",
                       {}};
    for (const double mg : {2.0, 3.0, 5.0})
      for (const double t : thetas_m3) {
        auto p = wedge(3, t, 1.0);
        p.granular_mach = mg;
        wt.points.push_back(p);
      }
    panels.push_back(wt);

    ParametricPanel wp{
        "wedge_packing",
        "Wedge at M = 3: shock angle against deflection, several inflow packing fractions",
        "theta_beta",
        {}};
    for (const double phi : {0.05, 0.1, 0.2})
      for (const double t : thetas_m3) {
        auto p = wedge(3, t, 1.0);
        p.packing = phi;
        wp.points.push_back(p);
      }
    panels.push_back(wp);
  }

  ParametricPanel dm{
      "disc_mach",
      "Disc: standoff against radius in particle diameters, several Mach numbers (e = 1)",
      "standoff",
      {}};
  for (const double m : quick ? std::vector<double>{4} : std::vector<double>{3, 4, 6})
    for (const double r : radii) dm.points.push_back(disc(m, r, 1.0));
  panels.push_back(dm);

  if (!quick) {
    ParametricPanel de{"disc_restitution",
                       "Disc at M = 4: standoff against radius, several restitutions",
                       "standoff",
                       {}};
    for (const double e : {1.0, 0.9})
      for (const double r : radii) de.points.push_back(disc(4, r, e));
    panels.push_back(de);

    ParametricPanel dt{"disc_temperature",
                       "Disc, gas M = 4: standoff against radius, several inflow temperatures",
                       "standoff",
                       {}};
    for (const double mg : {4.0, 6.0})
      for (const double r : radii) {
        auto p = disc(4, r, 1.0);
        p.granular_mach = mg;
        dt.points.push_back(p);
      }
    panels.push_back(dt);
  }

  // Mach sensitivity at fixed deflection; its e values bracket the
  // restitution at which the granular and gamma = 1.4 angles agree.
  const std::vector<double> machs =
      quick ? std::vector<double>{2, 4} : std::vector<double>{2, 3, 4, 6};
  const std::vector<double> es =
      quick ? std::vector<double>{1.0, 0.95} : std::vector<double>{1.0, 0.97, 0.9};
  for (const double t : quick ? std::vector<double>{10} : std::vector<double>{10, 20}) {
    ParametricPanel ms{
        "mach_theta" + fmt(t),
        "Wedge of " + fmt(t) + " deg: shock angle against Mach, several restitutions",
        "mach_beta",
        {}};
    for (const double e : es)
      for (const double m : machs)
        if (scene::oblique_shock_beta(m, t * kDeg, 1.4)) ms.points.push_back(wedge(m, t, e));
    panels.push_back(ms);
  }
  return panels;
}

std::string point_key(const ParametricPoint& p) {
  std::string k = p.body + "_M" + fmt(p.mach) + "_Mg" + fmt(p.granular_mach);
  k += p.body == "wedge" ? "_t" + fmt(p.theta_deg) + "_N" + std::to_string(p.particles)
                         : "_R" + fmt(p.radius_d);
  return k + "_e" + fmt(p.restitution) + "_phi" + fmt(p.packing) + "_avg" + fmt(p.averaging);
}

scene::Scene point_scene(const ParametricPoint& p) {
  std::string y = "name: " + point_key(p) + "\n";
  if (p.body == "wedge") {
    y += "body: {kind: wedge, angle_deg: " + fmt(p.theta_deg) + ", length: 1}\n";
  } else {
    y += "body: {kind: disc, radius: 0.5}\n";
  }
  y += "freestream: {mach: " + fmt(p.mach) + ", gamma: 1.4}\n";
  y += "granular: {restitution: " + fmt(p.restitution) +
       ", seed: 1, mach: " + fmt(p.granular_mach) + ", inflow_packing_fraction: " + fmt(p.packing) +
       ", averaging: " + fmt(p.averaging);
  // Every point at the replicas its recorded runs were made with (and cached
  // under, the key not naming them): bow shocks would otherwise get
  // kBowShockReplicas.
  y += ", replicas: " + std::to_string(scene::kDefaultReplicas);
  // A wedge's size is set by its disk count; a disc's radius in diameters is
  // the study's variable (its body length is the radius).
  y += p.body == "wedge" ? ", particles: " + std::to_string(p.particles)
                         : ", body_diameters: " + fmt(p.radius_d);
  y += "}\n";
  return scene::parse_scene(y, point_key(p));
}

bool is_case_study(const ParametricPoint& p) {
  if (p.body != "wedge") return false;
  constexpr double kSame = 1e-9;  // grid values are exact decimals
  for (const auto& [m, t] : {std::pair{3.0, 10.0}, {4.0, 15.0}, {5.0, 20.0}})
    if (std::abs(p.mach - m) < kSame && std::abs(p.theta_deg - t) < kSame) return true;
  return false;
}

}  // namespace pipeline
