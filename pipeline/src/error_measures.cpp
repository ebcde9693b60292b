#include "pipeline/error_measures.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "pipeline/bow_shock_check.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
using scene::kDeg;
using scene::kNaN;
// Stream-facing faces fitted for the stagnation pressure: within 20 degrees
// the Newtonian wall pressure p0 cos^2 + p_inf sin^2 differs from its
// quadratic in theta by under 0.2% of p0; at least three faces take part.
constexpr double kStagnationFitDeg = 20.0;
constexpr std::size_t kStagnationFitMinFaces = 3;
// Written times whose stagnation pressure bounds its uncertainty: two
// flow-throughs at the default write interval (0.2 flow-throughs). The
// stagnation point's state wanders by 1-2% over several flow-throughs after
// the global monitors call the run steady (docs/verdict.md).
constexpr std::size_t kStagnationWindowWrites = 10;

double polygon_area(const std::vector<scene::Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += scene::cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * std::abs(a);
}

// The CFD gas is normalised so that the free stream has p = T = 1 and
// rho = gamma (docs/units.md).
struct FreeStreamState {
  double rho, p;
};
FreeStreamState free_stream(const scene::Scene& s) {
  return {s.freestream.gamma, 1.0};
}

struct Solution {
  std::vector<double> rho, p;
  std::vector<std::array<double, 3>> u;
};

Solution read_solution(const std::string& case_dir, const cfd::TimeDir& t, std::size_t cells) {
  const std::string d = case_dir + "/" + t.name;
  return {cfd::read_scalar_field(d + "/rho", cells), cfd::read_scalar_field(d + "/p", cells),
          cfd::read_vector_field(d + "/U", cells)};
}

// The forebody ends at the body's widest section: behind it lies the wake,
// unsteady and not adiabatic to the scheme, where total enthalpy is no reference.
double forebody_end_x(const scene::BodySpec& b) { return scene::widest_section_x(scene::make_body(b)); }

// Largest change of the stagnation pressure over the last written times.
double stagnation_wander(const std::string& case_dir, const std::vector<cfd::TimeDir>& times,
                         const cfd::Mesh2D& mesh, double p_last) {
  double worst = 0;
  const std::size_t from =
      times.size() > kStagnationWindowWrites ? times.size() - kStagnationWindowWrites : 0;
  for (std::size_t i = from; i + 1 < times.size(); ++i) {
    const auto p = cfd::read_scalar_field(case_dir + "/" + times[i].name + "/p", mesh.cells());
    worst = std::max(worst, std::abs(stagnation_pressure(mesh, p) - p_last));
  }
  return worst;
}

double pressure_drag(const cfd::Mesh2D& mesh, const std::vector<double>& p, double p_inf) {
  double fx = 0;
  for (const auto& f : mesh.body)
    fx += (p[static_cast<std::size_t>(f.cell)] - p_inf) * f.normal_area.x;
  return fx;
}

MeasuredError from_pair(double last, double before, bool have_before) {
  return {last, have_before ? std::abs(last - before) : kNaN};
}
}  // namespace

double stagnation_pressure(const cfd::Mesh2D& mesh, const std::vector<double>& p) {
  struct Sample {
    double theta, p;
  };
  std::vector<Sample> faces;
  for (const auto& f : mesh.body) {
    // normal_area points out of the fluid: +x on a face that meets the stream head on.
    const double theta = std::atan2(std::abs(f.normal_area.y), f.normal_area.x);
    faces.push_back({theta, p[static_cast<std::size_t>(f.cell)]});
  }
  if (faces.empty()) return kNaN;
  std::sort(faces.begin(), faces.end(),
            [](const Sample& a, const Sample& b) { return a.theta < b.theta; });
  std::size_t n = 0;
  while (n < faces.size() && faces[n].theta <= kStagnationFitDeg * kDeg) ++n;
  n = std::min(faces.size(), std::max(n, kStagnationFitMinFaces));
  double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = faces[i].theta * faces[i].theta;
    s0 += 1;
    s1 += q;
    s2 += q * q;
    t0 += faces[i].p;
    t1 += q * faces[i].p;
  }
  const double det = s0 * s2 - s1 * s1;
  // Faces all at one angle (a flat or sharp nose) carry no curvature: their mean.
  if (!(det > 1e-12 * s2 * s0)) return t0 / s0;
  return (t0 * s2 - s1 * t1) / det;
}

double forebody_total_enthalpy_l1(const cfd::Mesh2D& mesh, const std::vector<double>& rho,
                                  const std::vector<double>& p,
                                  const std::vector<std::array<double, 3>>& u, double mach,
                                  double gamma, double x_max) {
  const double h_inf = 1.0 / (gamma - 1.0) + 0.5 * mach * mach;
  double sum = 0, area = 0;
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    if (mesh.cell_centre[c].x > x_max) continue;
    const double a = std::abs(mesh.cell_area[c]);
    const double h =
        gamma * p[c] / ((gamma - 1.0) * rho[c]) + 0.5 * (u[c][0] * u[c][0] + u[c][1] * u[c][1]);
    sum += std::abs(h / h_inf - 1.0) * a;
    area += a;
  }
  return area > 0 ? sum / area : kNaN;
}

double area_behind_line(const std::vector<scene::Vec2>& polygon, scene::Vec2 normal) {
  // Sutherland-Hodgman against one half-plane.
  std::vector<scene::Vec2> out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const scene::Vec2 a = polygon[i], b = polygon[(i + 1) % n];
    const double da = scene::dot(normal, a), db = scene::dot(normal, b);
    if (da < 0) out.push_back(a);
    if ((da < 0) != (db < 0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out.size() < 3 ? 0.0 : polygon_area(out);
}

std::vector<double> behind_fractions(const cfd::Mesh2D& mesh, double beta) {
  // Behind the shock (between the wall and the shock line) is n . p < 0.
  const scene::Vec2 n{-std::sin(beta), std::cos(beta)};
  std::vector<double> f(mesh.cells());
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    const double a = polygon_area(mesh.cell_polygons[c]);
    f[c] = std::min(a, area_behind_line(mesh.cell_polygons[c], n)) / a;
  }
  return f;
}

double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field,
                    const std::vector<double>& behind_fraction, double ahead, double behind,
                    double scale) {
  double sum = 0, area = 0;
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    const double a = std::abs(mesh.cell_area[c]);
    const double exact = ahead + (behind - ahead) * behind_fraction[c];
    sum += std::abs(field[c] - exact) * a;
    area += a;
  }
  return sum / (scale * area);
}

double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, double beta,
                    double ahead, double behind, double scale) {
  return piecewise_l1(mesh, field, behind_fractions(mesh, beta), ahead, behind, scale);
}

CaseErrors measure_case_errors(const scene::Scene& s, const std::string& case_dir) {
  CaseErrors e;
  if (!s.body) return e;
  const auto times = cfd::time_dirs(case_dir);
  if (times.empty()) throw scene::RunError(case_dir + ": no written solution to measure");
  const cfd::Mesh2D mesh = cfd::read_mesh_2d(case_dir);
  const FreeStreamState inf = free_stream(s);
  const double mach = s.freestream.mach, gamma = s.freestream.gamma;
  const bool have_before = times.size() >= 2;
  const Solution last = read_solution(case_dir, times.back(), mesh.cells());
  const Solution before =
      have_before ? read_solution(case_dir, times[times.size() - 2], mesh.cells()) : last;
  e.solutions_compared = have_before ? 2 : 1;

  if (const auto beta = scene::attached_shock_beta(s)) {
    const double rho2 = inf.rho * scene::oblique_density_ratio(mach, *beta, gamma);
    const double p2 = inf.p * scene::oblique_pressure_ratio(mach, *beta, gamma);
    // The cut cells' shares are the same for every field and time: clip once.
    const std::vector<double> fractions = behind_fractions(mesh, *beta);
    auto l1 = [&](const Solution& sol, bool density) {
      return density ? piecewise_l1(mesh, sol.rho, fractions, inf.rho, rho2, inf.rho)
                     : piecewise_l1(mesh, sol.p, fractions, inf.p, p2, inf.p);
    };
    e.l1_density = from_pair(l1(last, true), l1(before, true), have_before);
    e.l1_pressure = from_pair(l1(last, false), l1(before, false), have_before);
  }
  const double x_fore = forebody_end_x(*s.body);
  auto l1_h = [&](const Solution& sol) {
    return forebody_total_enthalpy_l1(mesh, sol.rho, sol.p, sol.u, mach, gamma, x_fore);
  };
  e.l1_total_enthalpy = from_pair(l1_h(last), l1_h(before), have_before);

  e.pitot_ratio = scene::rayleigh_pitot_ratio(mach, gamma);
  const double p_last = stagnation_pressure(mesh, last.p) / inf.p;
  e.stagnation_pressure_ratio = p_last;
  const double q_inf =
      0.5 * inf.rho * mach * mach;  // U = Mach in units of the free-stream sound speed
  e.drag_coefficient = pressure_drag(mesh, last.p, inf.p) / (q_inf * scene::body_length(*s.body));
  e.stagnation_pressure = {std::abs(p_last - e.pitot_ratio) / e.pitot_ratio,
                           have_before ? stagnation_wander(case_dir, times, mesh, p_last * inf.p) /
                                             (inf.p * e.pitot_ratio)
                                       : kNaN};

  if (!scene::attached_shock_beta(s)) {
    // The shock is marked halfway between the free stream and the normal-shock state.
    const double rho_mid =
        0.5 * inf.rho * (1.0 + scene::oblique_density_ratio(mach, 0.5 * std::numbers::pi, gamma));
    const scene::Vec2 nose = scene::make_body(*s.body).nose;
    e.shock_axis_deviation_cells =
        check_axis_shock(mesh, last.rho, rho_mid, nose.x, scene::correlation_nose_radius(*s.body))
            .deviation_cells;
  }
  return e;
}

MeasuredError measure_named(const CaseErrors& e, const std::string& name) {
  if (name == "l1_density") return e.l1_density;
  if (name == "l1_total_enthalpy") return e.l1_total_enthalpy;
  return e.stagnation_pressure;
}

}  // namespace pipeline
