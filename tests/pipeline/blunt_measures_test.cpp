// Blunt-body error measures on synthetic fields with known answers: the
// stagnation pressure fitted from the wall, the forebody total-enthalpy L1,
// and the carbuncle check of the bow shock at the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pipeline/bow_shock_check.hpp"
#include "pipeline/error_measures.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

// Wall faces of the upper half of a circle of radius R about the origin,
// each with its own fluid cell, faces every dtheta from theta0 on.
cfd::Mesh2D half_circle_wall(double r, double theta0, double dtheta, int faces) {
  cfd::Mesh2D m;
  for (int i = 0; i < faces; ++i) {
    const double t = theta0 + i * dtheta;
    const scene::Vec2 out{-std::cos(t), std::sin(t)};  // outward from the body, into the fluid
    const double len = r * dtheta;
    m.body.push_back({r * out, {-len * out.x, -len * out.y}, i});
  }
  return m;
}

TEST(StagnationPressure, FitReachesTheMaximumOfANewtonianWall) {
  // p = p0 cos^2 + p_inf sin^2: maximum p0 at theta = 0; the nearest face
  // sits half a face (3 degrees) off the axis.
  const double p0 = 21.07, pinf = 1.0, dt = 6 * kPi / 180;
  const auto m = half_circle_wall(0.5, 0.5 * dt, dt, 15);
  std::vector<double> p;
  for (const auto& f : m.body) {
    const double t = std::atan2(std::abs(f.normal_area.y), f.normal_area.x);
    p.push_back(p0 * std::cos(t) * std::cos(t) + pinf * std::sin(t) * std::sin(t));
  }
  // Within 20 degrees the Newtonian profile is quadratic in theta to 0.2 % of p0.
  EXPECT_NEAR(pipeline::stagnation_pressure(m, p), p0, 2e-3 * p0);
  EXPECT_LT(p[0], p0 * (1 - 2e-3));  // the nearest cell alone is further off
}

TEST(StagnationPressure, FitAveragesCellToCellScatter) {
  // A flat stagnation region with +-2 % odd-even scatter: the fit of its 7
  // faces within 20 degrees lands within the scatter's mean share (1/7 of 2 %).
  const double p0 = 32.65, dt = 3 * kPi / 180;
  const auto m = half_circle_wall(1.2, 0.5 * dt, dt, 20);
  std::vector<double> p;
  for (std::size_t i = 0; i < m.body.size(); ++i)
    p.push_back(p0 * (1 + (i % 2 == 0 ? 0.02 : -0.02)));
  const double fitted = pipeline::stagnation_pressure(m, p);
  EXPECT_NEAR(fitted, p0, 0.02 * p0);
  EXPECT_LT(std::abs(fitted - p0), std::abs(p[0] - p0));
}

TEST(StagnationPressure, FacesAllAtOneAngleGiveTheirMean) {
  // A flat face normal to the stream (a blunt base): no curvature to fit.
  cfd::Mesh2D m;
  for (int i = 0; i < 4; ++i) m.body.push_back({{0.0, 0.1 * i}, {0.1, 0.0}, i});
  EXPECT_NEAR(pipeline::stagnation_pressure(m, {10, 11, 12, 13}), 11.5, 1e-12);
}

TEST(TotalEnthalpyL1, ZeroForTheFreeStreamAndTheShockedStateAndKnownOtherwise) {
  // Three unit cells; the third lies behind the forebody's end and is ignored.
  cfd::Mesh2D m;
  m.cell_polygons = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                     {{1, 0}, {2, 0}, {2, 1}, {1, 1}},
                     {{2, 0}, {3, 0}, {3, 1}, {2, 1}}};
  m.cell_area = {1, 1, 1};
  m.cell_centre = {{0.5, 0.5}, {1.5, 0.5}, {2.5, 0.5}};
  const double g = 1.4, mach = 4.0;
  // Free stream (rho = gamma, p = 1, u = M) and the state at rest with the
  // free stream's total enthalpy (T0 = 1 + (g - 1) M^2 / 2).
  const double t0 = 1 + 0.5 * (g - 1) * mach * mach;
  std::vector<double> rho{g, g * 3.0, 1.0}, p{1.0, 3.0 * t0, 100.0};
  const std::vector<std::array<double, 3>> u{{mach, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  EXPECT_NEAR(pipeline::forebody_total_enthalpy_l1(m, rho, p, u, mach, g, 2.0), 0.0, 1e-14);
  // 10 % too hot at rest in the second cell: 10 % over half the forebody.
  p[1] *= 1.1;
  EXPECT_NEAR(pipeline::forebody_total_enthalpy_l1(m, rho, p, u, mach, g, 2.0), 0.05, 1e-14);
}

// A structured grid of square cells over [x0, x0 + nx h] x [0, ny h] with
// the density stepping from 1 to 5 across x = shock(y).
template <class Shock>
std::pair<cfd::Mesh2D, std::vector<double>> grid_with_shock(double x0, double h, int nx, int ny,
                                                            Shock shock) {
  cfd::Mesh2D m;
  std::vector<double> rho;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = x0 + i * h, y = j * h;
      m.cell_polygons.push_back({{x, y}, {x + h, y}, {x + h, y + h}, {x, y + h}});
      m.cell_area.push_back(h * h);
      m.cell_centre.push_back({x + 0.5 * h, y + 0.5 * h});
      rho.push_back(x + 0.5 * h < shock(y + 0.5 * h) ? 1.0 : 5.0);
    }
  return {m, rho};
}

TEST(CarbuncleCheck, SmoothBowShockPassesABumpAtTheAxisIsFlagged) {
  const double h = 0.02;
  auto smooth = [](double y) { return -0.8 + 0.3 * y * y; };
  const auto [m, rho] = grid_with_shock(-1.2, h, 60, 30, smooth);
  const auto ok = pipeline::check_axis_shock(m, rho, 3.0, -0.5, 0.5);
  EXPECT_GT(ok.fit_points, 10);
  EXPECT_GT(ok.axis_points, 0);
  EXPECT_NEAR(ok.cell_size, h, 1e-12);
  EXPECT_LT(ok.deviation_cells, 1.0);  // the staircase of a captured shock: under a cell
  // A carbuncle: the shock pushed 5 cells upstream within 2 cells of the axis.
  auto bumped = [&](double y) { return smooth(y) - (y < 2 * h ? 5 * h : 0.0); };
  const auto [mb, rhob] = grid_with_shock(-1.2, h, 60, 30, bumped);
  const auto bad = pipeline::check_axis_shock(mb, rhob, 3.0, -0.5, 0.5);
  EXPECT_GT(bad.deviation_cells, pipeline::kCarbuncleCells);
  EXPECT_NEAR(bad.deviation_cells, 5.0, 1.0);
}

TEST(CarbuncleCheck, NoShockGivesNaN) {
  const auto [m, rho] = grid_with_shock(-1.2, 0.02, 20, 10, [](double) { return 10.0; });
  EXPECT_TRUE(std::isnan(pipeline::check_axis_shock(m, rho, 3.0, 0.0, 0.5).deviation_cells));
}

}  // namespace
