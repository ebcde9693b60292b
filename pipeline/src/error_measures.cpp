#include "pipeline/error_measures.hpp"

#include <cmath>
#include <filesystem>

#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
using scene::kNaN;

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
FreeStreamState free_stream(const scene::Scene& s) { return {s.freestream.gamma, 1.0}; }

struct Solution {
  std::vector<double> rho, p;
};

Solution read_solution(const std::string& case_dir, const cfd::TimeDir& t, std::size_t cells) {
  const std::string d = case_dir + "/" + t.name;
  return {cfd::read_scalar_field(d + "/rho", cells), cfd::read_scalar_field(d + "/p", cells)};
}

// Pressure at the stagnation point: the fluid cell of the body face nearest
// the body's nose. The wall-normal and wall-tangential pressure gradients
// both vanish there in inviscid flow, so the cell value is second-order close.
double stagnation_pressure(const cfd::Mesh2D& mesh, const std::vector<double>& p, scene::Vec2 nose) {
  double best = 1e300;
  long cell = -1;
  for (const auto& f : mesh.body) {
    const double d = scene::norm2(f.centre - nose);
    if (d < best) {
      best = d;
      cell = f.cell;
    }
  }
  return cell >= 0 ? p[static_cast<std::size_t>(cell)] : kNaN;
}

double pressure_drag(const cfd::Mesh2D& mesh, const std::vector<double>& p, double p_inf) {
  double fx = 0;
  for (const auto& f : mesh.body) fx += (p[static_cast<std::size_t>(f.cell)] - p_inf) * f.normal_area.x;
  return fx;
}

MeasuredError from_pair(double last, double before, bool have_before) {
  return {last, have_before ? std::abs(last - before) : kNaN};
}
}  // namespace

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

double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, const std::vector<double>& behind_fraction,
                    double ahead, double behind, double scale) {
  double sum = 0, area = 0;
  for (std::size_t c = 0; c < mesh.cells(); ++c) {
    const double a = std::abs(mesh.cell_area[c]);
    const double exact = ahead + (behind - ahead) * behind_fraction[c];
    sum += std::abs(field[c] - exact) * a;
    area += a;
  }
  return sum / (scale * area);
}

double piecewise_l1(const cfd::Mesh2D& mesh, const std::vector<double>& field, double beta, double ahead,
                    double behind, double scale) {
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
  const Solution before = have_before ? read_solution(case_dir, times[times.size() - 2], mesh.cells()) : last;
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
  e.pitot_ratio = scene::rayleigh_pitot_ratio(mach, gamma);
  const scene::Vec2 nose = scene::make_body(*s.body).nose;
  const double p_last = stagnation_pressure(mesh, last.p, nose) / inf.p;
  const double p_before = stagnation_pressure(mesh, before.p, nose) / inf.p;
  e.stagnation_pressure_ratio = p_last;
  const double q_inf = 0.5 * inf.rho * mach * mach;  // U = Mach in units of the free-stream sound speed
  e.drag_coefficient = pressure_drag(mesh, last.p, inf.p) / (q_inf * scene::body_length(*s.body));
  e.stagnation_pressure = from_pair(std::abs(p_last - e.pitot_ratio) / e.pitot_ratio,
                                    std::abs(p_before - e.pitot_ratio) / e.pitot_ratio, have_before);
  return e;
}

}  // namespace pipeline
