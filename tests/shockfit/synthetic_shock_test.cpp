// The locator on fields with a known shock: a noisy tanh oblique shock, the
// exact inviscid oblique shock on a lattice, Billig's bow shock, and a
// subsonic field.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"
#include "shockfit/locate.hpp"
#include "synthetic.hpp"

namespace {

using scene::kDeg;

scene::Scene wedge_scene(double mach, double angle_deg) {
  return scene::parse_scene("name: w\nbody: {kind: wedge, angle_deg: " + std::to_string(angle_deg) +
                            ", length: 1.0}\nfreestream: {mach: " + std::to_string(mach) + "}\n");
}

// Oblique shock through the apex at angle beta: distance above the shock.
double above_shock(double x, double y, double beta) { return y * std::cos(beta) - x * std::sin(beta); }

}  // namespace

TEST(ObliqueShock, NoisyTanhAngleAndPosition) {
  // Mach 3, 10 deg wedge, shock at the exact angle, tanh of width one cell,
  // noise 10% of the jump (seed 11). The angle within 0.2 deg; each shock
  // point within half a lattice spacing (rms; max without noise).
  const double mach = 3.0, theta = 10.0 * kDeg, h = 0.005, width = h;
  const double beta = *scene::oblique_shock_beta(mach, theta, 1.4);
  const double r2 = scene::oblique_density_ratio(mach, beta, 1.4);
  for (const double noise : {0.0, 0.1}) {
    scene::Scene s = wedge_scene(mach, 10.0);
    s.shockfit.field = "rho";
    scene::Lattice lat = shockfit_test::domain_lattice(s, h);
    const std::uint64_t seed = 11;
    shockfit_test::fill(lat, "rho", [&](double x, double y) {
      return 1.0 + (r2 - 1.0) * 0.5 * (1.0 - std::tanh(above_shock(x, y, beta) / width));
    }, noise * (r2 - 1.0), seed);
    const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
    ASSERT_EQ(r.shock, scene::ShockKind::attached) << "noise " << noise;
    constexpr double kAngleTolDeg = 0.2;
    EXPECT_NEAR(r.shock_angle_deg, beta / kDeg, kAngleTolDeg) << "noise " << noise << " seed " << seed;
    EXPECT_GT(r.shock_angle_ci_deg, 0.0);
    EXPECT_LT(r.shock_angle_ci_deg, 1.0);
    double sum2 = 0.0, worst = 0.0;
    int n = 0;
    for (const auto& f : r.stations) {
      if (!f.accepted || f.station == 0) continue;
      // Exact distance along the normal from the surface point to the shock.
      const scene::Vec2 grad{-std::sin(beta), std::cos(beta)};
      const double t = -above_shock(f.surface.x, f.surface.y, beta) / scene::dot(f.normal, grad);
      sum2 += (f.distance - t) * (f.distance - t);
      worst = std::max(worst, std::abs(f.distance - t));
      ++n;
    }
    ASSERT_GE(n, s.shockfit.stations * 3 / 4) << "most stations find the shock";
    constexpr double kHalfCell = 0.5;
    if (noise == 0.0) {
      EXPECT_LT(worst, kHalfCell * h);
    }
    EXPECT_LT(std::sqrt(sum2 / n), kHalfCell * h) << "noise " << noise << " seed " << seed;
  }
}

TEST(ObliqueShock, WideShockIsFound) {
  // A shock five cells wide (granular shocks span several cells) with the
  // default four-cell window: the window widens per station until the jump
  // is accepted. A window only a little wider than the shock leaves a bias
  // (measured -0.37 deg mean over 20 seeds), hence the looser tolerance.
  const double mach = 3.0, theta = 10.0 * kDeg, h = 0.005, width = 5 * h;
  const double beta = *scene::oblique_shock_beta(mach, theta, 1.4);
  const double r2 = scene::oblique_density_ratio(mach, beta, 1.4);
  scene::Scene s = wedge_scene(mach, 10.0);
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  const std::uint64_t seed = 13;
  shockfit_test::fill(lat, "volume_fraction", [&](double x, double y) {
    return 0.1 * (1.0 + (r2 - 1.0) * 0.5 * (1.0 - std::tanh(above_shock(x, y, beta) / width)));
  }, 0.05 * 0.1 * (r2 - 1.0), seed);
  const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
  ASSERT_EQ(r.shock, scene::ShockKind::attached) << "seed " << seed;
  EXPECT_GE(r.accepted_count(), s.shockfit.stations * 3 / 4);
  constexpr double kWideShockTolDeg = 0.75;
  EXPECT_NEAR(r.shock_angle_deg, beta / kDeg, kWideShockTolDeg) << "seed " << seed;
}

TEST(ObliqueShock, ExactInviscidSolutionOnLattice) {
  // The exact solution (free stream / uniform post-shock state, cell
  // averaged) for each wedge case: the theta-beta-Mach angle within 0.1 deg,
  // with auto's joint density and v shock.
  for (const char* name : {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20"}) {
    const scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    const double mach = s.freestream.mach, theta = s.body->angle_deg * kDeg, gamma = s.freestream.gamma;
    const double beta = *scene::oblique_shock_beta(mach, theta, gamma);
    const double r2 = scene::oblique_density_ratio(mach, beta, gamma);
    const double v2 = scene::oblique_downstream_mach(mach, beta, theta, gamma) * std::sin(theta);  // any scale
    const double h = 0.005;
    scene::Lattice lat = shockfit_test::domain_lattice(s, h);
    constexpr int kSub = 6;
    shockfit_test::fill_cell_average(lat, "rho", [&](double x, double y) {
      return above_shock(x, y, beta) > 0 ? 1.0 : r2;
    }, kSub);
    shockfit_test::fill_cell_average(lat, "v", [&](double x, double y) {
      return above_shock(x, y, beta) > 0 ? 0.0 : v2;
    }, kSub);
    const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
    ASSERT_EQ(r.shock, scene::ShockKind::attached) << name;
    constexpr double kExactTolDeg = 0.1;
    EXPECT_NEAR(r.shock_angle_deg, beta / kDeg, kExactTolDeg) << name << " field " << r.field;
    EXPECT_EQ(r.field, "rho+v");  // auto fits both jointly
    EXPECT_TRUE(r.candidates.contains("rho") && r.candidates.contains("v"));
  }
}

TEST(ObliqueShock, AJumpOnTheStagnationLineAloneLeavesTheShockAttached) {
  // Mach 4.5, 12 deg: the exact attached shock, and a clump of denser gas
  // on the axis 0.14-0.3 body lengths ahead of the apex (a granular run can
  // throw disks back off the apex), which the stagnation line sees as a
  // jump. The shock points all meet at the apex, none ahead of it: the
  // shock stays attached, at its angle.
  const double mach = 4.5, theta = 12.0 * kDeg, h = 0.005;
  const double beta = *scene::oblique_shock_beta(mach, theta, 1.4);
  const double r2 = scene::oblique_density_ratio(mach, beta, 1.4);
  const double v2 = scene::oblique_downstream_mach(mach, beta, theta, 1.4) * std::sin(theta);
  const scene::Scene s = wedge_scene(mach, 12.0);
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  auto clump = [&](double x, double y) { return x > -0.3 && x < -0.14 && std::abs(y) < 3 * h; };
  shockfit_test::fill(
      lat, "volume_fraction",
      [&](double x, double y) {
        return clump(x, y) || above_shock(x, y, beta) <= 0 ? 0.1 * r2 : 0.1;
      },
      0.0, 1);
  shockfit_test::fill(
      lat, "v", [&](double x, double y) { return above_shock(x, y, beta) > 0 ? 0.0 : v2; }, 0.0, 2);
  const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
  ASSERT_TRUE(r.stagnation.accepted) << "the clump must be seen on the stagnation line";
  EXPECT_GT(r.stagnation.distance, 0.1);
  ASSERT_EQ(r.shock, scene::ShockKind::attached);
  constexpr double kExactTolDeg = 0.1;
  EXPECT_NEAR(r.shock_angle_deg, beta / kDeg, kExactTolDeg);
}

TEST(BowShock, BilligStandoff) {
  // Billig's bow shock ahead of the Mach 4 disc, tanh of width one cell,
  // noise 5% of the jump: standoff within 2%, shock detached.
  const scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/disc_M4.yaml");
  const double mach = s.freestream.mach, R = s.body->radius;
  const double delta = scene::billig_standoff_cylinder(mach) * R;
  const double xv = -R - delta;
  const double r2 = scene::oblique_density_ratio(mach, std::numbers::pi / 2, 1.4);
  const double h = 0.005, width = h;
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  auto dist = [&](double x, double y) {  // signed, downstream positive
    const double xs = xv + scene::billig_shock_x(mach, R, y);
    const double dy = 1e-6;
    const double slope = (scene::billig_shock_x(mach, R, y + dy) - scene::billig_shock_x(mach, R, y - dy)) / (2 * dy);
    return (x - xs) / std::sqrt(1.0 + slope * slope);
  };
  const std::uint64_t seed = 5;
  shockfit_test::fill(lat, "volume_fraction", [&](double x, double y) {
    return 0.1 * (1.0 + (r2 - 1.0) * 0.5 * (1.0 + std::tanh(dist(x, y) / width)));
  }, 0.05 * 0.1 * (r2 - 1.0), seed);
  const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
  ASSERT_EQ(r.shock, scene::ShockKind::detached);
  EXPECT_EQ(r.field, "volume_fraction");
  const double expected = delta / R;  // body length = disc radius
  constexpr double kStandoffRelTol = 0.02;
  EXPECT_NEAR(r.standoff, expected, kStandoffRelTol * expected) << "seed " << seed;
  EXPECT_GT(r.standoff_ci, 0.0);
  EXPECT_LT(r.standoff_ci, kStandoffRelTol * expected);
  // The near-axis shape: vertex and curvature radius of Billig's hyperbola.
  EXPECT_NEAR(r.vertex_x, xv, 2 * h);
  const double rc = scene::billig_shock_radius_cylinder(mach);  // in nose radii = body lengths
  EXPECT_NEAR(r.curvature_radius, rc, 0.15 * rc);
  EXPECT_GE(r.accepted_count(), s.shockfit.stations / 2);
}

TEST(Subsonic, NoShock) {
  // Incompressible potential flow around a disc with the isentropic density
  // of Mach 0.5: smooth everywhere, so no station finds a jump. (The default
  // blunt-body domain is sized for a bow shock; a subsonic one is smaller.)
  for (const double noise : {0.0, 0.005}) {
    const scene::Scene s = scene::parse_scene("name: sub\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 0.5}\n"
                                                "domain: {xmin: -2.5, xmax: 0.5, ymin: 0, ymax: 2.5, symmetric: true}\n");
    const double R = 0.5, mach = 0.5, gamma = 1.4;
    scene::Lattice lat = shockfit_test::domain_lattice(s, 0.005);
    auto q2 = [&](double x, double y) {
      const double r2 = x * x + y * y, c2 = (x * x - y * y) / r2;
      return 1.0 + R * R * R * R / (r2 * r2) - 2.0 * R * R / r2 * c2;
    };
    shockfit_test::fill(lat, "rho", [&](double x, double y) {
      return std::pow(1.0 + 0.5 * (gamma - 1.0) * mach * mach * (1.0 - q2(x, y)), 1.0 / (gamma - 1.0));
    }, noise, 21);
    shockfit_test::fill(lat, "v", [&](double x, double y) {
      const double r2 = x * x + y * y;
      return -R * R * 2.0 * x * y / (r2 * r2);
    }, noise, 22);
    const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
    EXPECT_EQ(r.shock, scene::ShockKind::none) << "noise " << noise;
    EXPECT_EQ(r.accepted_count(), 0) << "noise " << noise;
    EXPECT_TRUE(std::isnan(r.shock_angle_deg) && std::isnan(r.standoff));
  }
}

TEST(Errors, MissingFieldIsInputError) {
  const scene::Scene s = wedge_scene(3.0, 10.0);
  scene::Lattice lat = shockfit_test::domain_lattice(s, 0.02);
  lat.add("temperature", 1.0);
  try {
    (void)shockfit::locate_shock(s, lat);
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none of the fields shockfit can use"), std::string::npos) << e.what();
  }
}

TEST(Errors, LatticeOutsideDomainIsInputError) {
  const scene::Scene s = wedge_scene(3.0, 10.0);
  scene::Lattice lat(10, 10, 50.0, 50.0, 0.1, 0.1);
  lat.add("rho", 1.0);
  try {
    (void)shockfit::locate_shock(s, lat);
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("which misses the domain of scene 'w'"), std::string::npos) << e.what();
  }
}
