#include "pipeline/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

std::vector<CostError> costs(const std::vector<VerdictRun>& runs, bool total, double predictor_cpu) {
  std::vector<CostError> out;
  for (const auto& r : runs)
    out.push_back({total ? predictor_cpu + r.mesh_cpu + r.cfd_cpu : r.cfd_cpu, r.error, r.error_ci});
  return out;
}
}  // namespace

PrimaryError primary_error_for(const scene::Scene& s) {
  if (scene::reference_is_exact_oblique_shock(s))
    return {"l1_density",
            "exact oblique-shock solution (theta-beta-Mach), averaged over each CFD cell",
            "the attached-wedge flow is piecewise constant, so the L1 density error against the exact cell averages "
            "measures the whole field, shock position and smearing included, with no reference grid"};
  return {"stagnation_pressure",
          "Rayleigh pitot formula (exact for inviscid flow)",
          "the stagnation-point pressure has an exact value behind any bow shock (normal shock, then isentropic "
          "compression), so it needs no reference grid; standoff and shape are shown beside it"};
}

Verdict make_verdict(const PrimaryError& primary, const std::vector<VerdictRun>& clustered,
                     const std::vector<VerdictRun>& uniform, double predictor_cpu) {
  Verdict v;
  v.primary = primary;
  v.predictor_cpu = predictor_cpu;
  v.speedup_cfd = v.speedup_total = {kNaN, kNaN, kNaN};
  v.target_error = kNaN;
  const auto c = usable_runs(clustered, v.clustered);
  const auto u = usable_runs(uniform, v.uniform);
  v.clustered.cfd = fit_log_log(costs(c, false, 0));
  v.clustered.total = fit_log_log(costs(c, true, predictor_cpu));
  v.uniform.cfd = fit_log_log(costs(u, false, 0));
  v.uniform.total = fit_log_log(costs(u, true, 0));
  if (c.empty() || u.empty()) {
    v.note = "a family has no usable run";
    return v;
  }
  // The headline error: the finest clustered grid that counts.
  const auto finest = std::min_element(c.begin(), c.end(), [](const VerdictRun& a, const VerdictRun& b) {
    return a.level < b.level;
  });
  v.target_error = finest->error;
  double u_lo = 1e300, u_hi = 0;
  for (const auto& r : u) {
    u_lo = std::min(u_lo, r.error);
    u_hi = std::max(u_hi, r.error);
  }
  v.extrapolated = v.target_error < u_lo || v.target_error > u_hi;
  v.speedup_cfd = cost_ratio_at_error(costs(u, false, 0), costs(c, false, 0), v.target_error);
  v.speedup_total = cost_ratio_at_error(costs(u, true, 0), costs(c, true, predictor_cpu), v.target_error);
  v.verdict = verdict_of(v.speedup_total);
  v.verdict_cfd = verdict_of(v.speedup_cfd);
  if (!std::isfinite(v.speedup_cfd.value))
    v.note = "a family has fewer than 3 usable runs or its error does not fall with cost: no fit";
  else if (v.extrapolated)
    v.note = "the clustered error lies outside the uniform family's range: the uniform fit is extrapolated";
  return v;
}

nlohmann::json interval_json(const Interval& i) {
  auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"value", num(i.value)}, {"ci_low", num(i.ci_low)}, {"ci_high", num(i.ci_high)}};
}

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
          {"target_error", std::isfinite(v.target_error) ? nlohmann::json(v.target_error) : nlohmann::json(nullptr)},
          {"extrapolated", v.extrapolated},
          {"speedup_cfd", interval_json(v.speedup_cfd)},
          {"speedup_total", interval_json(v.speedup_total)},
          {"verdict", v.verdict},
          {"verdict_cfd", v.verdict_cfd},
          {"predictor_cpu_seconds", v.predictor_cpu},
          {"families", {{"clustered", fam(v.clustered)}, {"uniform", fam(v.uniform)}}},
          {"note", v.note}};
}

}  // namespace pipeline
