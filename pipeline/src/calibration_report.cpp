#include "pipeline/calibration_report.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "pipeline/restitution_crossing.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;
// Digits shown: e to 1e-4 (its interval is ~1e-3), angles to 0.01 deg.
constexpr int kRestitutionDecimals = 4;
constexpr int kAngleDecimals = 2;

double num(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(decimals);
  os << v;
  return os.str();
}

std::string general(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

nlohmann::json rms_max(const std::vector<double>& errors) {
  if (errors.empty()) return {{"n", 0}, {"rms_deg", nullptr}, {"max_abs_deg", nullptr}};
  double ss = 0, mx = 0;
  for (const double x : errors) {
    ss += x * x;
    mx = std::max(mx, std::abs(x));
  }
  return {{"n", errors.size()},
          {"rms_deg", std::sqrt(ss / static_cast<double>(errors.size()))},
          {"max_abs_deg", mx}};
}

const nlohmann::json* chosen(const nlohmann::json& c) {
  for (const auto& f : c.at("candidates"))
    if (f.value("model", "") == c.value("model", "")) return &f;
  return nullptr;
}
}  // namespace

nlohmann::json local_correction_json(const std::optional<LocalCorrection>& c) {
  if (!c) return nullptr;
  return {{"h_log_mach", c->bandwidth_log_mach},
          {"h_angle_deg", c->bandwidth_angle_deg},
          {"loo_rms", c->loo_rms}};
}

nlohmann::json out_of_sample_summary(const nlohmann::json& c) {
  std::vector<double> loo, cases;
  for (const auto& p : c.at("points"))
    if (std::isfinite(num(p, "loo_angle_error_deg"))) loo.push_back(num(p, "loo_angle_error_deg"));
  for (const auto& k : c.at("case_studies"))
    if (!k.value("in_sample", false) && std::isfinite(num(k, "angle_error_deg")))
      cases.push_back(num(k, "angle_error_deg"));
  const auto* f = chosen(c);
  return {{"leave_one_out", rms_max(loo)},
          {"case_studies", rms_max(cases)},
          {"residual_sd_restitution", f ? num(*f, "residual_sd") : kNaN}};
}

std::string calibration_markdown(const nlohmann::json& c) {
  std::ostringstream md;
  const auto* f = chosen(c);
  const auto& s = c.at("summary");
  md << "Target: the gamma = " << general(num(c, "target_gamma"), 3)
     << " theta-beta-Mach shock angle. e swept over";
  for (const auto& e : c.at("restitutions")) md << " " << e.get<double>();
  md << ", then " << c.value("refinements", 0) << " run(s) bisecting the bracketing interval; "
     << c.value("seeds", 1) << " run(s) per e at seeds " << kSeedStride
     << " apart, their inverse-variance mean the point; crossing on a weighted parabola through "
        "the points within "
     << c.value("crossing_window", kNaN)
     << " of the bracket's where there are three, else interpolated across the bracket (95% "
        "half-width from the fit's covariance, or the bracket's intervals over its slope).\n\n";

  md << "| model | coefficients | sd of e about the fit | leave-one-out RMS of e (weighted) "
        "|\n|---|---|---|---|\n";
  for (const auto& m : c.at("candidates")) {
    const bool is_chosen = m.value("model", "") == c.value("model", "");
    md << "| " << (is_chosen ? "**" : "") << m.value("formula", "")
       << (is_chosen ? "** (chosen)" : "") << " |";
    const auto& co = m.at("coefficients");
    for (std::size_t i = 0; i < co.size(); ++i)
      md << (i ? ", " : " ") << "c" << i << " = " << general(co[i].get<double>(), 6);
    md << " | " << general(num(m, "residual_sd"), 3) << " | " << general(num(m, "loo_rms"), 3)
       << " |\n";
  }
  if (const auto lc = c.find("local_correction"); lc != c.end() && lc->is_object())
    md << "\nThe chosen model keeps a local correction: a Gaussian-kernel average of its "
          "residuals at the training wedges (widths "
       << general(num(*lc, "h_log_mach"), 3) << " in ln M, " << general(num(*lc, "h_angle_deg"), 3)
       << " deg in theta), leave-one-out RMS of e " << general(num(*lc, "loo_rms"), 3)
       << " against the model's own above.\n";
  md << "\nResidual scatter of e about the chosen fit (sd, n - p degrees of freedom): "
     << general(f ? num(*f, "residual_sd") : kNaN, 3) << ".\n\n";

  md << "Leave-one-out: each training wedge refitted without it and run at that fit's e with seed "
        "granular.seed + "
     << c.at("seed_offsets").value("leave_one_out", 0)
     << " (one run; the sweeps used the seeds above).\n\n";
  md << "| point (M / theta) | crossing e +- 95% | e_fit (left out) | granular angle +- 95% (deg) "
        "| gas angle (deg) "
        "| error (deg) |\n|---|---|---|---|---|---|\n";
  for (const auto& p : c.at("points")) {
    md << "| " << general(num(p, "mach"), 3) << " / " << general(num(p, "angle_deg"), 3) << " | "
       << fixed(num(p, "restitution"), kRestitutionDecimals) << " +- "
       << fixed(num(p, "restitution_ci"), kRestitutionDecimals) << " | "
       << fixed(num(p, "loo_restitution"), kRestitutionDecimals) << " | "
       << fixed(num(p, "loo_granular_angle_deg"), kAngleDecimals) << " +- "
       << fixed(num(p, "loo_granular_angle_ci_deg"), kAngleDecimals) << " | "
       << fixed(num(p, "gas_angle_deg"), kAngleDecimals) << " | "
       << fixed(num(p, "loo_angle_error_deg"), kAngleDecimals) << " |\n";
  }
  std::ostringstream steps;
  int n_steps = 0;
  for (const auto& p : c.at("points"))
    if (p.value("on_step", false))
      steps << (n_steps++ ? ", " : "") << general(num(p, "mach"), 3) << " / "
            << general(num(p, "angle_deg"), 3);
  if (n_steps > 0)
    md << "\n**" << n_steps
       << " crossing(s) on a step of angle(e)** (the bracket rises several times faster than "
          "the segment above it): "
       << steps.str()
       << ". There the gas angle is met only at the step's foot, and an e a little lower "
          "reads degrees lower (docs/calibration.md).\n";
  const auto& l = s.at("leave_one_out");
  md << "\nOut-of-sample angle error over " << l.value("n", 0) << " wedges: RMS "
     << fixed(num(l, "rms_deg"), kAngleDecimals) << " deg, max |error| "
     << fixed(num(l, "max_abs_deg"), kAngleDecimals) << " deg.\n\n";

  md << "Case studies (not training points) at the fitted e, seed granular.seed + "
     << c.at("seed_offsets").value("case_studies", 0) << ":\n\n";
  md << "| case | e_fit | granular angle +- 95% (deg) | gas angle (deg) | error (deg) "
        "|\n|---|---|---|---|---|\n";
  for (const auto& k : c.at("case_studies")) {
    md << "| " << k.value("scene", "")
       << (k.value("in_sample", false) ? " (in the training set)" : "") << " | "
       << fixed(num(k, "restitution"), kRestitutionDecimals) << " | "
       << fixed(num(k, "granular_angle_deg"), kAngleDecimals) << " +- "
       << fixed(num(k, "granular_angle_ci_deg"), kAngleDecimals) << " | "
       << fixed(num(k, "gas_angle_deg"), kAngleDecimals) << " | "
       << fixed(num(k, "angle_error_deg"), kAngleDecimals) << " |\n";
  }
  const auto& cs = s.at("case_studies");
  md << "\nCase-study angle error: RMS " << fixed(num(cs, "rms_deg"), kAngleDecimals)
     << " deg, max |error| " << fixed(num(cs, "max_abs_deg"), kAngleDecimals) << " deg.\n\n";
  const auto& cpu = c.at("cpu_seconds");
  md << "CPU: " << fixed(num(cpu, "sweeps"), 0) << " s for the sweeps, "
     << fixed(num(cpu, "out_of_sample"), 0) << " s for the out-of-sample runs, "
     << fixed(num(cpu, "total"), 0)
     << " s in all (a cached run counts what it cost when it ran; this process "
     << fixed(num(cpu, "this_process"), 0) << " s); wall " << fixed(num(c, "wall_seconds"), 0)
     << " s.\n";
  if (c.value("bow_shock_kept", false))
    md << "\nThe table's bow_shock block (and its shape fits) is kept: it records the e(M) its "
          "blunt bodies ran at, and blunt bodies keep that law.\n";
  return md.str();
}

}  // namespace pipeline
