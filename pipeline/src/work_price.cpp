#include "pipeline/work_price.hpp"

#include <algorithm>
#include <cmath>

namespace pipeline {

namespace {

struct Line {
  double base = 0, slope = 0;
};

// y = base + slope x by least squares on relative residuals (timing noise
// is multiplicative), both coefficients kept non-negative: a negative
// overhead or cost per cell is noise, not a machine.
Line fit_relative(const std::vector<double>& x, const std::vector<double>& y) {
  Line l;
  for (int pass = 0; pass < 3; ++pass) {  // reweight by the model, not the noisy sample
    double sw = 0, swx = 0, swy = 0, swxx = 0, swxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double model = pass == 0 ? y[i] : l.base + l.slope * x[i];
      const double w = 1.0 / std::max(model * model, 1e-300);
      sw += w;
      swx += w * x[i];
      swy += w * y[i];
      swxx += w * x[i] * x[i];
      swxy += w * x[i] * y[i];
    }
    const double det = sw * swxx - swx * swx;
    Line next;
    if (det > 0) {
      next.slope = (sw * swxy - swx * swy) / det;
      next.base = (swy - next.slope * swx) / sw;
    }
    if (!(det > 0) || next.base < 0) next = {0.0, swxx > 0 ? swxy / swxx : 0.0};
    if (next.slope < 0) next = {swy / sw, 0.0};
    l = next;
  }
  return l;
}

double log_sd(const std::vector<double>& x, const std::vector<double>& y, const Line& l) {
  double ss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = std::log(y[i] / (l.base + l.slope * x[i]));
    ss += r * r;
  }
  constexpr int kCoefficients = 2;
  return std::sqrt(ss / static_cast<double>(std::max<std::size_t>(1, x.size() - kCoefficients)));
}

bool usable(const WorkRun& r) {
  return r.cells > 0 && r.steps > 0 && std::isfinite(r.cfd_cpu) && r.cfd_cpu > 0 && std::isfinite(r.mesh_cpu) &&
         r.mesh_cpu > 0;
}

WorkPrice fit_on(const std::vector<WorkRun>& runs, double cfd_factor_sd, double mesh_factor_sd,
                 std::mt19937_64* rng) {
  std::vector<double> cells, per_step, mesh;
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& r : runs) {
    if (!usable(r)) continue;
    const double fc = rng ? std::exp(cfd_factor_sd * normal(*rng)) : 1.0;
    const double fm = rng ? std::exp(mesh_factor_sd * normal(*rng)) : 1.0;
    cells.push_back(static_cast<double>(r.cells));
    per_step.push_back(fc * r.cfd_cpu / static_cast<double>(r.steps));
    mesh.push_back(fm * r.mesh_cpu);
  }
  WorkPrice p;
  constexpr std::size_t kMinRuns = 3;  // two coefficients and one degree of freedom for the scatter
  p.runs = static_cast<int>(cells.size());
  if (cells.size() < kMinRuns) return p;
  const Line c = fit_relative(cells, per_step);
  const Line m = fit_relative(cells, mesh);
  p.per_step = c.base;
  p.per_cell_step = c.slope;
  p.mesh_base = m.base;
  p.mesh_per_cell = m.slope;
  p.cfd_log_sd = log_sd(cells, per_step, c);
  p.mesh_log_sd = log_sd(cells, mesh, m);
  p.ok = c.base + c.slope > 0 && m.base + m.slope > 0 && std::isfinite(p.cfd_log_sd) && std::isfinite(p.mesh_log_sd);
  return p;
}

}  // namespace

double WorkPrice::cfd(const WorkRun& r) const {
  return static_cast<double>(r.steps) * (per_step + per_cell_step * static_cast<double>(r.cells));
}

double WorkPrice::mesh(const WorkRun& r) const { return mesh_base + mesh_per_cell * static_cast<double>(r.cells); }

WorkPrice fit_work_price(const std::vector<WorkRun>& runs) { return fit_on(runs, 0, 0, nullptr); }

WorkPrice draw_work_price(const std::vector<WorkRun>& runs, const WorkPrice& fitted, std::mt19937_64& rng) {
  return fit_on(runs, fitted.cfd_log_sd, fitted.mesh_log_sd, &rng);
}

}  // namespace pipeline
