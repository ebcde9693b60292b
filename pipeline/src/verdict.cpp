#include "pipeline/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <tuple>

#include "json_fields.hpp"
#include "scene/body_traits.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;

std::string run_name(const VerdictRun& r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_h%g", r.family.c_str(), r.level);
  return buf;
}

// Runs that may enter a fit: steady, with a positive finite error and cost.
std::vector<VerdictRun> usable_runs(const std::vector<VerdictRun>& runs, FamilyFitInfo& info) {
  std::vector<VerdictRun> out;
  for (const auto& r : runs) {
    if (!r.steady) info.excluded.push_back(run_name(r) + ": did not reach steady state");
    else if (!(std::isfinite(r.error) && r.error > 0)) info.excluded.push_back(run_name(r) + ": no error measured");
    else if (!(r.cfd_cpu > 0)) info.excluded.push_back(run_name(r) + ": no CPU time");
    else out.push_back(r);
  }
  info.used = static_cast<int>(out.size());
  return out;
}

WorkRun work_of(const VerdictRun& r) { return {r.cells, r.steps, r.cfd_cpu, r.mesh_cpu}; }

std::vector<WorkRun> work_of(const std::vector<VerdictRun>& a, const std::vector<VerdictRun>& b) {
  std::vector<WorkRun> out;
  for (const auto* fam : {&a, &b})
    for (const auto& r : *fam) out.push_back(work_of(r));
  return out;
}

bool has_work(const std::vector<VerdictRun>& runs) {
  return std::all_of(runs.begin(), runs.end(), [](const VerdictRun& r) { return r.cells > 0 && r.steps > 0; });
}

// A family's (cost, error) points: CFD CPU alone, or with the grid's
// meshing (`total`; the predictor, paid once per family, is the pair's fixed
// cost); priced by `price` when given.
std::vector<CostError> costs(const std::vector<VerdictRun>& runs, bool total,
                             const WorkPrice* price) {
  std::vector<CostError> out;
  for (const auto& r : runs) {
    const WorkRun w = work_of(r);
    const double cfd = price ? price->cfd(w) : r.cfd_cpu;
    const double mesh = price ? price->mesh(w) : r.mesh_cpu;
    out.push_back({total ? mesh + cfd : cfd, r.error, r.error_ci});
  }
  return out;
}

// The smallest and largest primary error among the runs.
std::pair<double, double> error_range(const std::vector<VerdictRun>& runs) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const auto& r : runs) {
    lo = std::min(lo, r.error);
    hi = std::max(hi, r.error);
  }
  return {lo, hi};
}

// Both families' points; with `total`, each family's predictor as its fixed cost.
FamilyPair family_pair(const std::vector<VerdictRun>& u, const std::vector<VerdictRun>& c,
                       bool total, double u_predictor, double c_predictor, const WorkPrice* price) {
  return {costs(u, total, price), costs(c, total, price), total ? u_predictor : 0.0,
          total ? c_predictor : 0.0};
}

// The speedups with the price's and the predictor timing's uncertainty drawn
// in every Monte Carlo sample.
std::pair<Interval, Interval> priced_speedups(const Verdict& v, const std::vector<VerdictRun>& c,
                                              const std::vector<VerdictRun>& u, double u_predictor,
                                              double target) {
  const std::vector<WorkRun> work = work_of(c, u);
  const WorkPrice fitted = v.price;
  const double predictor = v.predictor_cpu;
  auto sampler = [&](bool total) {
    return [&, total](std::mt19937_64& rng) {
      const WorkPrice p = draw_work_price(work, fitted, rng);
      const WorkPrice& use = p.ok ? p : fitted;
      // The scatter itself is estimated from the fit's residuals (runs - 2
      // degrees of freedom): drawn from its chi-square, so one timing's
      // deviation follows a Student t rather than a normal.
      std::normal_distribution<double> normal(0.0, 1.0);
      const int dof = std::max(1, fitted.runs - 2);
      std::chi_squared_distribution<double> chi2(dof);
      const double sd = fitted.cfd_log_sd * std::sqrt(dof / std::max(chi2(rng), 1e-300));
      const double pred = predictor * std::exp(sd * normal(rng));
      const double u_pred = u_predictor > 0 ? u_predictor * std::exp(sd * normal(rng)) : 0.0;
      return family_pair(u, c, total, u_pred, pred, &use);
    };
  };
  return {cost_ratio_at_error(family_pair(u, c, false, 0, 0, &fitted), sampler(false), target),
          cost_ratio_at_error(family_pair(u, c, true, u_predictor, predictor, &fitted),
                              sampler(true), target)};
}
}  // namespace

PrimaryError primary_error_for(const scene::Scene& s) {
  if (scene::reference_is_exact_oblique_shock(s))
    return {"l1_density",
            "exact oblique-shock solution (theta-beta-Mach), averaged over each CFD cell",
            "the attached-wedge flow is piecewise constant, so the L1 density error against the exact cell averages "
            "measures the whole field, shock position and smearing included, with no reference grid"};
  return {"l1_total_enthalpy",
          "free-stream total enthalpy (exact for steady inviscid adiabatic flow, across shocks too)",
          "the total enthalpy is the free stream's everywhere ahead of the body's widest section, so its L1 error "
          "over the forebody measures the captured bow shock's smearing and the errors it leaves behind with no "
          "reference grid; the stagnation-point value (Rayleigh pitot) reads one streamline and does not converge "
          "monotonically on these grids, so it is shown beside it"};
}

Verdict make_verdict(const PrimaryError& primary, const std::vector<VerdictRun>& clustered,
                     const std::vector<VerdictRun>& uniform, double predictor_cpu, double uniform_predictor_cpu) {
  Verdict v;
  v.primary = primary;
  v.predictor_cpu = predictor_cpu;
  v.speedup_cfd = v.speedup_total = {kNaN, kNaN, kNaN};
  v.target_error = kNaN;
  const auto c = usable_runs(clustered, v.clustered);
  const auto u = usable_runs(uniform, v.uniform);
  if (has_work(c) && has_work(u)) v.price = fit_work_price(work_of(c, u));
  v.priced = v.price.ok;
  const WorkPrice* price = v.priced ? &v.price : nullptr;
  v.clustered.cfd = fit_log_log(costs(c, false, price));
  v.clustered.total = fit_log_log(costs(c, true, price));
  v.uniform.cfd = fit_log_log(costs(u, false, price));
  v.uniform.total = fit_log_log(costs(u, true, price));
  if (c.empty() || u.empty()) {
    v.note = "a family has no usable run";
    return v;
  }
  // The headline error: the finest clustered grid that counts.
  const auto finest = std::min_element(c.begin(), c.end(), [](const VerdictRun& a, const VerdictRun& b) {
    return a.level < b.level;
  });
  const auto [u_lo, u_hi] = error_range(u);
  const double c_hi = error_range(c).second;
  v.target_error = finest->error;
  if (finest->error < u_lo && u_lo <= c_hi) {
    v.beyond_uniform.error = finest->error;
    v.target_error = u_lo;
  }
  v.extrapolated = v.target_error < u_lo || v.target_error > u_hi;
  v.measured_cfd = cost_ratio_at_error(family_pair(u, c, false, 0, 0, nullptr), v.target_error);
  v.measured_total = cost_ratio_at_error(
      family_pair(u, c, true, uniform_predictor_cpu, predictor_cpu, nullptr), v.target_error);
  const auto speedups = [&](double target) -> std::pair<Interval, Interval> {
    if (v.priced) return priced_speedups(v, c, u, uniform_predictor_cpu, target);
    return {cost_ratio_at_error(family_pair(u, c, false, 0, 0, nullptr), target),
            cost_ratio_at_error(
                family_pair(u, c, true, uniform_predictor_cpu, predictor_cpu, nullptr), target)};
  };
  std::tie(v.speedup_cfd, v.speedup_total) = speedups(v.target_error);
  if (std::isfinite(v.beyond_uniform.error))
    std::tie(v.beyond_uniform.speedup_cfd, v.beyond_uniform.speedup_total) =
        speedups(v.beyond_uniform.error);
  v.verdict = verdict_of(v.speedup_total);
  v.verdict_cfd = verdict_of(v.speedup_cfd);
  if (!v.priced)
    v.note = "fewer than three runs with cells, steps and CPU: costs are the measured single timings";
  if (!std::isfinite(v.speedup_cfd.value))
    v.note = "a family has fewer than 3 usable runs or its error does not fall with cost: no fit";
  else if (v.extrapolated)
    v.note = "the clustered error lies outside the uniform family's range: the uniform fit is extrapolated";
  else if (std::isfinite(v.beyond_uniform.error))
    v.note =
        "the clustered finest error lies below every uniform grid's: the speedup is read at the "
        "uniform "
        "finest's error, inside both families' ranges (at the clustered finest, extrapolating the "
        "uniform "
        "fit: beyond_uniform_range)";
  return v;
}

void charge_calibration(Verdict& v, const std::vector<VerdictRun>& clustered, const std::vector<VerdictRun>& uniform,
                        double calibration_cpu, int scenes_served) {
  if (!std::isfinite(calibration_cpu)) return;
  const Verdict alone = make_verdict(v.primary, clustered, uniform, v.predictor_cpu + calibration_cpu);
  v.calibration.cpu_seconds = calibration_cpu;
  v.calibration.scenes_served = scenes_served;
  v.calibration.speedup_total_if_alone = alone.speedup_total;
  v.calibration.verdict_if_alone = alone.verdict;
}

nlohmann::json interval_json(const Interval& i) {
  return {{"value", json_number(i.value)}, {"ci_low", json_number(i.ci_low)}, {"ci_high", json_number(i.ci_high)}};
}

double verdict_cfd_cpu(const Verdict& v, long cells, long steps, double measured) {
  return v.priced ? v.price.cfd({cells, steps, measured, 0}) : measured;
}

double verdict_mesh_cpu(const Verdict& v, long cells, long steps, double measured) {
  return v.priced ? v.price.mesh({cells, steps, 0, measured}) : measured;
}

namespace {
nlohmann::json price_json(const Verdict& v) {
  if (!v.priced) return {{"model", "measured"}};
  const WorkPrice& p = v.price;
  return {{"model", "priced"},
          {"runs", p.runs},
          {"cfd_seconds_per_step", p.per_step},
          {"cfd_us_per_cell_step", p.per_cell_step * 1e6},
          {"mesh_base_seconds", p.mesh_base},
          {"mesh_us_per_cell", p.mesh_per_cell * 1e6},
          {"cfd_timing_log_sd", p.cfd_log_sd},
          {"mesh_timing_log_sd", p.mesh_log_sd}};
}

nlohmann::json beyond_json(const Verdict::BeyondUniform& b) {
  if (!std::isfinite(b.error)) return nullptr;
  return {{"target_error", b.error},
          {"speedup_cfd", interval_json(b.speedup_cfd)},
          {"speedup_total", interval_json(b.speedup_total)}};
}

nlohmann::json calibration_json(const Verdict::Calibration& c) {
  if (!std::isfinite(c.cpu_seconds)) return nullptr;
  return {{"cpu_seconds", c.cpu_seconds},
          {"scenes_served", c.scenes_served},
          {"cpu_seconds_per_scene", c.scenes_served > 0 ? c.cpu_seconds / c.scenes_served : c.cpu_seconds},
          {"speedup_total_if_alone", interval_json(c.speedup_total_if_alone)},
          {"verdict_if_alone", c.verdict_if_alone}};
}
}  // namespace

nlohmann::json verdict_json(const Verdict& v) {
  auto fit = [](const LogLogFit& f) {
    if (!f.ok) return nlohmann::json(nullptr);
    return nlohmann::json{{"log_error_intercept", f.a}, {"slope", f.b}, {"residual_sd", f.residual_sd}, {"runs", f.n}};
  };
  auto fam = [&](const FamilyFitInfo& f) {
    return nlohmann::json{{"runs_used", f.used}, {"excluded", f.excluded}, {"fit_cfd", fit(f.cfd)},
                          {"fit_total", fit(f.total)}};
  };
  return {{"primary_error", v.primary.name},
          {"primary_error_reference", v.primary.reference},
          {"target_error", json_number(v.target_error)},
          {"extrapolated", v.extrapolated},
          {"beyond_uniform_range", beyond_json(v.beyond_uniform)},
          {"speedup_cfd", interval_json(v.speedup_cfd)},
          {"speedup_total", interval_json(v.speedup_total)},
          {"verdict", v.verdict},
          {"verdict_cfd", v.verdict_cfd},
          {"predictor_cpu_seconds", v.predictor_cpu},
          {"cost", price_json(v)},
          {"calibration", calibration_json(v.calibration)},
          {"measured_cpu",
           {{"speedup_cfd", interval_json(v.measured_cfd)},
            {"speedup_total", interval_json(v.measured_total)},
            {"verdict", verdict_of(v.measured_total)}}},
          {"families", {{"clustered", fam(v.clustered)}, {"uniform", fam(v.uniform)}}},
          {"note", v.note}};
}

}  // namespace pipeline
