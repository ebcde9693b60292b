#include "case_monitor.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "foam_process.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gnuplot.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace cfd {
namespace fs = std::filesystem;

namespace {
// Part of the wedge face (fraction of its length from the apex) over which
// the wall pressure is averaged: away from the apex, where the shock forms
// over the first cells, and from the outflow boundary.
constexpr double kWallWindowStart = 0.25;
constexpr double kWallWindowEnd = 0.9;
// Guard against division by a vanishing body force.
constexpr double kTinyForce = 1e-300;

// The steady rule judges the force on the body's upstream-facing faces (the
// forebody), whose flow the shock sets: past a blunt body's shoulder the flow
// is supersonic, so the wake behind it cannot reach back, and it settles far
// more slowly (Apollo's afterbody force still drifted by 0.5 % per
// flow-through after 15 flow-throughs while the forebody error had not moved
// in its fourth digit since 9). Face vectors point out of the fluid, into the
// body: an upstream-facing face has a positive x component.
bool faces_upstream(const WallFace& f) {
  return f.normal_area.x > 0.0;
}
}  // namespace

CaseReader::CaseReader(const scene::Scene& s, const std::string& case_dir, int np) : case_dir_(case_dir) {
  if (np > 1) {
    for (int k = 0; k < np; ++k) part_dirs_.push_back(case_dir + "/processor" + std::to_string(k));
  } else {
    part_dirs_.push_back(case_dir);
  }
  for (const auto& d : part_dirs_) parts_.push_back(read_mesh_2d(d));
  probe_ = ShockProbe::for_scene(s, parts_);
  const std::optional<double> ramp = s.body ? scene::straight_ramp_length(*s.body) : std::nullopt;
  wedge_ = ramp.has_value();
  if (wedge_) wedge_length_ = *ramp;
  p_inf_ = freestream(s).p;
}

std::vector<TimeDir> CaseReader::times_after(double after) const {
  std::vector<TimeDir> out;
  for (const TimeDir& t : time_dirs(part_dirs_.front()))
    if (t.time > after) out.push_back(t);
  return out;
}

long CaseReader::cells() const {
  long n = 0;
  for (const auto& m : parts_) n += static_cast<long>(m.cells());
  return n;
}

Snapshot CaseReader::read(const TimeDir& t) const {
  Snapshot s;
  s.time = t.time;
  s.name = t.name;
  double wall_pa = 0, wall_a = 0;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const Mesh2D& m = parts_[k];
    const std::string dir = part_dirs_[k] + "/" + t.name;
    const auto rho = read_scalar_field(dir + "/rho", m.cells());
    const auto p = read_scalar_field(dir + "/p", m.cells());
    for (std::size_t c = 0; c < m.cells(); ++c) {
      if (!(std::isfinite(rho[c]) && std::isfinite(p[c]) && rho[c] > 0 && p[c] > 0))
        throw NonPhysicalState(fmt::format("the solution diverged: rho = {}, p = {} in cell {} at time {} ({})",
                                          rho[c], p[c], c, t.name, dir));
    }
    s.rho.insert(s.rho.end(), rho.begin(), rho.end());
    for (const WallFace& f : m.body) {
      const double pw = p[static_cast<std::size_t>(f.cell)];
      if (faces_upstream(f)) {
        s.force.x += pw * f.normal_area.x;
        s.force.y += pw * f.normal_area.y;
      }
      const double frac = std::hypot(f.centre.x, f.centre.y) / wedge_length_;
      if (frac >= kWallWindowStart && frac <= kWallWindowEnd) {
        const double a = std::hypot(f.normal_area.x, f.normal_area.y);
        wall_pa += pw * a;
        wall_a += a;
      }
    }
  }
  s.wall_pressure_ratio = wedge_ && wall_a > 0 ? wall_pa / wall_a / p_inf_ : scene::kNaN;
  if (probe_) s.shock = probe_->measure(s.rho);
  return s;
}

HistoryRow compare(const Snapshot& prev, const Snapshot& cur, const std::vector<Mesh2D>& parts,
                   double rho_inf, double flow_through) {
  HistoryRow r;
  r.time = cur.time;
  r.flow_throughs = cur.time / flow_through;
  r.force = cur.force;
  r.wall_pressure_ratio = cur.wall_pressure_ratio;
  const double per = flow_through / (cur.time - prev.time);  // per flow-through time
  double sum = 0, area = 0, mx = 0;
  std::size_t i = 0;
  for (const Mesh2D& m : parts) {
    for (std::size_t c = 0; c < m.cells(); ++c, ++i) {
      const double d = cur.rho[i] - prev.rho[i];
      sum += m.cell_area[c] * d * d;
      area += m.cell_area[c];
      mx = std::max(mx, std::abs(d));
    }
  }
  r.drho_l2 = std::sqrt(sum / area) / rho_inf * per;
  r.drho_max = mx / rho_inf * per;
  const double fm = std::max(std::hypot(cur.force.x, cur.force.y), kTinyForce);
  r.dforce = std::hypot(cur.force.x - prev.force.x, cur.force.y - prev.force.y) / fm * per;
  r.shock_x = cur.shock.x;
  r.shock_cell = cur.shock.cell;
  r.dshock = (cur.shock.x - prev.shock.x) * per;
  return r;
}

void write_history(const std::string& case_dir, const std::vector<HistoryRow>& rows, double steady_tol,
                   double force_tol, bool plot) {
  // The shock columns come last, so readers of the older columns by
  // position keep working; a value not measured is an empty field.
  const auto opt = [](double v) {
    return std::isfinite(v) ? fmt::format("{:.8g}", v) : std::string();
  };
  std::ostringstream o;
  o << "time,flow_throughs,wall_seconds,steps,drho_l2,drho_max,dforce,force_x,force_y,"
       "wall_pressure_ratio,shock_x,dshock,shock_drift,shock_cell\n";
  for (const HistoryRow& r : rows)
    o << fmt::format(
        "{:.10g},{:.6g},{:.4f},{},{:.6e},{:.6e},{:.6e},{:.10g},{:.10g},{:.10g},{},{},{},{}\n",
        r.time, r.flow_throughs, r.wall_seconds, r.steps, r.drho_l2, r.drho_max, r.dforce,
        r.force.x, r.force.y, r.wall_pressure_ratio, opt(r.shock_x), opt(r.dshock),
        opt(r.shock_drift), opt(r.shock_cell));
  scene::write_file_atomic(case_dir + "/history.csv", o.str());
  if (rows.empty() || !plot) return;
  // The plot is for people; a missing gnuplot leaves only the CSV.
  const std::string gp = fmt::format(
      "set terminal pngcairo size 900,600\n"
      "set output 'history.png'\n"
      "set datafile separator ','\n"
      "set logscale y\n"
      "set format y '%.0e'\n"
      "set xlabel 'flow-through times'\n"
      "set ylabel 'relative change per flow-through time'\n"
      "set title 'steady-state history (rhoCentralFoam)'\n"
      "set key top right\n"
      "plot 'history.csv' using 2:5 skip 1 with linespoints title 'density L2', \\\n"
      "     '' using 2:6 skip 1 with linespoints title 'density max', \\\n"
      "     '' using 2:7 skip 1 with linespoints title 'body force', \\\n"
      "     {:.6g} with lines dashtype 2 title 'steady tol', \\\n"
      "     {:.6g} with lines dashtype 3 title 'force tol'\n",
      steady_tol, force_tol);
  scene::write_file_atomic(case_dir + "/history.gp", gp);
  try {
    scene::run_gnuplot(case_dir + "/history.gp", case_dir, case_dir + "/log.gnuplot");
  } catch (const scene::RunError&) {
    // Best effort, as above: log.gnuplot says why.
  }
}

}  // namespace cfd
