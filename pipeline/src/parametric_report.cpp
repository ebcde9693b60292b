// The parametric study's tables, figures, calibration training file and
// page, all from the rows (no runs here).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "json_fields.hpp"
#include "pipeline/parametric.hpp"
#include "pipeline/plot.hpp"
#include "pipeline/studies.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/gnuplot.hpp"
#include "scene/io.hpp"
#include "scene/shock_kind.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using scene::kDeg;
constexpr double kGammaAir = 1.4;
constexpr double kGammaDisks = 2.0;  // dilute hard disks
constexpr double kCurveStepDeg = 0.25;
constexpr double kCurveMachStep = 0.05;
constexpr double kSameValue = 1e-9;       // grid values are exact decimals
constexpr double kDetachedPlotBeta = 90;  // detached granular shocks drawn at beta = 90 deg

// A number of a row, NaN when missing (one rule across the pipeline).
double d(const Json& r, const char* k) { return number_or_nan(r, k); }

std::string fmt(double v, int digits = 3) {
  if (!std::isfinite(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

bool resolved(const Json& r) {
  return r.value("resolved", true);
}

bool in_panel(const Json& r, const std::string& id) {
  for (const auto& p : r["panels"])
    if (p.get<std::string>() == id) return true;
  return false;
}

std::vector<Json> panel_rows(const Json& rows, const std::string& id) {
  std::vector<Json> out;
  for (const auto& r : rows)
    if (in_panel(r, id)) out.push_back(r);
  return out;
}

// The series a panel's rows fall into: the parameters that vary across the
// panel, other than its x axis.
std::string series_label(const Json& r, const std::vector<Json>& rows, const std::string& x) {
  auto varies = [&](const char* k) {
    if (x == k) return false;
    return std::any_of(rows.begin(), rows.end(),
                       [&](const Json& o) { return std::abs(d(o, k) - d(r, k)) > kSameValue; });
  };
  const bool mg_is_m = std::all_of(rows.begin(), rows.end(), [](const Json& o) {
    return std::abs(d(o, "granular_mach") - d(o, "mach")) < kSameValue;
  });
  std::vector<std::string> parts;
  if (varies("mach")) parts.push_back("M = " + fmt(d(r, "mach")));
  if (varies("granular_mach") && !mg_is_m)
    parts.push_back("granular M = " + fmt(d(r, "granular_mach")));
  if (varies("restitution")) parts.push_back("e = " + fmt(d(r, "restitution")));
  if (varies("packing")) parts.push_back("phi = " + fmt(d(r, "packing")));
  if (parts.empty()) return "granular";
  std::string s = parts[0];
  for (std::size_t k = 1; k < parts.size(); ++k) s += ", " + parts[k];
  return s;
}

std::map<std::string, std::vector<Json>> by_series(const std::vector<Json>& rows, const char* x) {
  std::map<std::string, std::vector<Json>> out;
  for (const auto& r : rows) out[series_label(r, rows, x)].push_back(r);
  for (auto& [k, v] : out)
    std::sort(v.begin(), v.end(), [&](const Json& a, const Json& b) { return d(a, x) < d(b, x); });
  return out;
}

std::set<double> distinct(const std::vector<Json>& rows, const char* k) {
  std::set<double> s;
  for (const auto& r : rows)
    if (std::isfinite(d(r, k))) s.insert(d(r, k));
  return s;
}

Series theta_beta_curve(double mach, double gamma, const std::string& title,
                        const std::string& style) {
  Series s{title, {}, {}, {}, style};
  const double top = scene::max_deflection(mach, gamma) / kDeg;
  for (double t = kCurveStepDeg; t < top; t += kCurveStepDeg)
    if (const auto b = scene::oblique_shock_beta(mach, t * kDeg, gamma)) {
      s.x.push_back(t);
      s.y.push_back(*b / kDeg);
    }
  return s;
}

std::string vline(double x, const std::string& text) {
  return "set arrow from " + fmt(x, 5) + ", graph 0 to " + fmt(x, 5) +
         ", graph 1 nohead dt 3 lc rgb 'gray40'\n" + "set label " + scene::gnuplot_string(text) +
         " at " + fmt(x, 5) + ", graph 0.03 rotate by 90 offset -0.6,0 font ',8' tc rgb 'gray30'";
}

// Mean of granular minus reference over the attached points.
struct Offset {
  double mean = scene::kNaN, max_abs = 0;
  int n = 0, within_ci = 0;
};
Offset offset(const std::vector<Json>& rows, const char* ref) {
  Offset o;
  double sum = 0;
  for (const auto& r : rows) {
    const double b = d(r, "beta_deg"), g = d(r, ref), ci = d(r, "beta_ci_deg");
    if (!resolved(r) || !std::isfinite(b) || !std::isfinite(g)) continue;
    sum += b - g;
    o.max_abs = std::max(o.max_abs, std::abs(b - g));
    ++o.n;
    if (std::abs(b - g) <= ci) ++o.within_ci;
  }
  if (o.n) o.mean = sum / o.n;
  return o;
}

std::string theta_beta_panel(const ParametricPanel& panel, const Json& rows,
                             const std::string& png) {
  const auto pr = panel_rows(rows, panel.id);
  PlotSpec spec{panel.title,
                "wedge deflection theta (deg)",
                "shock angle beta (deg)",
                false,
                false,
                {},
                {},
                1100,
                650};
  spec.extra.push_back("set key outside right top font ',9'");
  spec.extra.push_back("set yrange [0:" + fmt(kDetachedPlotBeta + 2) + "]");
  for (const double m : distinct(pr, "mach")) {
    spec.series.push_back(
        theta_beta_curve(m, kGammaAir, "gas gamma 1.4, M = " + fmt(m), "lines lw 2"));
    spec.extra.push_back(
        vline(scene::max_deflection(m, kGammaAir) / kDeg, "detach 1.4, M " + fmt(m)));
  }
  for (const double m : distinct(pr, "granular_mach")) {
    spec.series.push_back(
        theta_beta_curve(m, kGammaDisks, "disk gas gamma 2, M = " + fmt(m), "lines dt 2 lw 1.5"));
    spec.extra.push_back(
        vline(scene::max_deflection(m, kGammaDisks) / kDeg, "detach 2, M " + fmt(m)));
  }
  std::ostringstream md;
  Series detached{"granular: detached (drawn at 90 deg)", {}, {}, {}, "points pt 6 ps 1.5"};
  for (const auto& [label, rs] : by_series(pr, "theta_deg")) {
    Series s{"granular, " + label + " (95%)", {}, {}, {}, ""};
    double first_detached = scene::kNaN;
    std::string unresolved;
    for (const auto& r : rs) {
      if (!resolved(r))
        unresolved += " " + fmt(d(r, "theta_deg")) + " (" +
                      (std::isfinite(d(r, "beta_deg"))
                           ? fmt(d(r, "beta_deg")) + " ± " + fmt(d(r, "beta_ci_deg"))
                           : r.value("shock", "")) +
                      ")";
      if (resolved(r)) {
        s.x.push_back(d(r, "theta_deg"));
        s.y.push_back(d(r, "beta_deg"));
        s.yerr.push_back(d(r, "beta_ci_deg"));
      } else if (scene::shock_kind_from(r.value("shock", "")) == scene::ShockKind::detached) {
        detached.x.push_back(d(r, "theta_deg"));
        detached.y.push_back(kDetachedPlotBeta);
        if (!std::isfinite(first_detached)) first_detached = d(r, "theta_deg");
      }
    }
    spec.series.push_back(s);
    const Offset air = offset(rs, "gas_beta_deg"), disks = offset(rs, "disk_gas_beta_deg");
    md << "- " << label << ": " << air.n << " resolved shocks; granular minus gamma 1.4 "
       << fmt(air.mean, 2) << " deg on average (largest " << fmt(air.max_abs, 2) << ", "
       << air.within_ci << " of " << air.n
       << " within their 95% interval); minus gamma 2 at the granular Mach " << fmt(disks.mean, 2)
       << " deg (largest " << fmt(disks.max_abs, 2) << ", " << disks.within_ci << " within).";
    if (std::isfinite(first_detached))
      md << " Detached from " << fmt(first_detached) << " deg (gamma 2 detaches at "
         << fmt(d(rs.front(), "disk_max_deflection_deg")) << ", gamma 1.4 at "
         << fmt(d(rs.front(), "max_deflection_deg")) << ").";
    if (!unresolved.empty()) md << " No resolved shock at theta (deg):" << unresolved << ".";
    md << "\n";
  }
  if (!detached.x.empty()) spec.series.push_back(detached);
  plot_png(spec, png);
  return md.str();
}

std::string standoff_panel(const ParametricPanel& panel, const Json& rows, const std::string& png) {
  const auto pr = panel_rows(rows, panel.id);
  PlotSpec spec{
      panel.title, "disc radius R (particle diameters)", "standoff / R", true, false, {}, {}, 1100,
      650};
  spec.extra.push_back("set key outside right top font ',9'");
  const auto radii = distinct(pr, "radius_d");
  std::ostringstream md;
  for (const auto& [label, rs] : by_series(pr, "radius_d")) {
    Series s{"granular, " + label + " (95%)", {}, {}, {}, ""};
    std::vector<Json> ok;
    for (const auto& r : rs)
      if (std::isfinite(d(r, "standoff"))) {
        s.x.push_back(d(r, "radius_d"));
        s.y.push_back(d(r, "standoff"));
        s.yerr.push_back(d(r, "standoff_ci"));
        ok.push_back(r);
      }
    spec.series.push_back(s);
    md << "- " << label << ": standoff/R ";
    for (const auto& r : rs)
      md << fmt(d(r, "standoff"))
         << (std::isfinite(d(r, "standoff_ci")) ? " ± " + fmt(d(r, "standoff_ci"), 2) : "")
         << " at R = " << fmt(d(r, "radius_d")) << " d"
         << (std::isfinite(d(r, "standoff")) ? ""
                                             : " (" + r.value("shock", r.value("status", "")) + ")")
         << "; ";
    if (!ok.empty()) {
      md << "Billig (gamma 1.4) " << fmt(d(ok.back(), "billig_standoff"))
         << ", ratio at the largest radius "
         << fmt(d(ok.back(), "standoff") / d(ok.back(), "billig_standoff")) << ". ";
      // Continuum limit: from the smallest radius on which every larger one
      // agrees with its neighbour within their combined 95% intervals.
      std::size_t from = ok.size() - 1;
      while (from > 0) {
        const auto& a = ok[from - 1];
        const auto& b = ok[from];
        const double ci = std::hypot(d(a, "standoff_ci"), d(b, "standoff_ci"));
        if (!(std::abs(d(a, "standoff") - d(b, "standoff")) <= ci)) break;
        --from;
      }
      if (ok.size() >= 2 && from + 1 < ok.size())
        md << "Size-independent within the intervals from R = " << fmt(d(ok[from], "radius_d"))
           << " d.";
      else
        md << "Still changing with size at the largest radius: no continuum limit by R = "
           << fmt(d(ok.back(), "radius_d")) << " d.";
    }
    md << "\n";
  }
  if (!radii.empty())
    for (const double m : distinct(pr, "mach")) {
      const double b = scene::billig_standoff_cylinder(m);
      spec.series.push_back({"Billig cylinder, M = " + fmt(m),
                             {*radii.begin(), *radii.rbegin()},
                             {b, b},
                             {},
                             "lines dt 2 lw 2"});
    }
  plot_png(spec, png);
  return md.str();
}

Series beta_mach_curve(double theta_deg, double gamma, double m_lo, double m_hi,
                       const std::string& title, const std::string& style) {
  Series s{title, {}, {}, {}, style};
  for (double m = m_lo; m <= m_hi; m += kCurveMachStep)
    if (const auto b = scene::oblique_shock_beta(m, theta_deg * kDeg, gamma)) {
      s.x.push_back(m);
      s.y.push_back(*b / kDeg);
    }
  return s;
}

std::string mach_beta_panel(const ParametricPanel& panel, const Json& rows,
                            const std::string& png) {
  const auto pr = panel_rows(rows, panel.id);
  PlotSpec spec{panel.title, "Mach number", "shock angle beta (deg)", false, false, {}, {}, 1100,
                650};
  spec.extra.push_back("set key outside right top font ',9'");
  const auto ms = distinct(pr, "mach");
  const auto ts = distinct(pr, "theta_deg");
  std::ostringstream md;
  if (ms.empty() || ts.empty()) return md.str();
  const double theta = *ts.begin();
  const double lo = std::max(1.05, *ms.begin() - 0.5), hi = *ms.rbegin() + 0.5;
  spec.series.push_back(beta_mach_curve(theta, kGammaAir, lo, hi, "gas gamma 1.4", "lines lw 2"));
  spec.series.push_back(
      beta_mach_curve(theta, kGammaDisks, lo, hi, "disk gas gamma 2", "lines dt 2 lw 1.5"));
  {
    Series mu{"Mach angle", {}, {}, {}, "lines dt 3 lc rgb 'gray50'"};
    for (double m = lo; m <= hi; m += kCurveMachStep) {
      mu.x.push_back(m);
      mu.y.push_back(std::asin(1.0 / m) / kDeg);
    }
    spec.series.push_back(mu);
  }
  for (const auto& [label, rs] : by_series(pr, "mach")) {
    Series s{"granular, " + label + " (95%)", {}, {}, {}, ""};
    md << "- " << label << ": granular minus gamma 1.4 ";
    for (const auto& r : rs) {
      if (resolved(r)) {
        s.x.push_back(d(r, "mach"));
        s.y.push_back(d(r, "beta_deg"));
        s.yerr.push_back(d(r, "beta_ci_deg"));
      }
      md << fmt(d(r, "beta_deg") - d(r, "gas_beta_deg"), 2) << " ± " << fmt(d(r, "beta_ci_deg"), 2)
         << " deg at M " << fmt(d(r, "mach")) << (resolved(r) ? "" : " (unresolved)") << "; ";
    }
    spec.series.push_back(s);
    md << "\n";
  }
  plot_png(spec, png);
  return md.str();
}

std::string calibration_panel(const std::vector<Crossing>& cs, const std::string& png) {
  PlotSpec spec{"Restitution at which the granular shock angle equals the gamma = 1.4 angle",
                "Mach number",
                "restitution e",
                false,
                false,
                {},
                {},
                1000,
                600};
  std::map<double, Series> by_theta;
  std::ostringstream md;
  for (const auto& c : cs) {
    md << "- theta " << fmt(c.theta_deg) << " deg, M " << fmt(c.mach) << ": ";
    if (!c.found) {
      md << c.note << "\n";
      continue;
    }
    md << "e = " << fmt(c.restitution, 4) << " ± " << fmt(c.ci, 2)
       << (c.note.empty() ? "" : " (" + c.note + ")") << "\n";
    auto& s = by_theta[c.theta_deg];
    s.title = "theta = " + fmt(c.theta_deg) + " deg (95%)";
    s.x.push_back(c.mach);
    s.y.push_back(c.restitution);
    s.yerr.push_back(c.ci);
  }
  for (auto& [t, s] : by_theta) spec.series.push_back(s);
  plot_png(spec, png);
  return md.str();
}

struct Mean {
  double sum = 0;
  int n = 0;
  void add(double v) {
    if (std::isfinite(v)) sum += v, ++n;
  }
  double value() const { return n ? sum / n : scene::kNaN; }
};

// The page's opening reading: the panels' numbers pooled.
std::string reading(const Json& rows, const std::vector<Crossing>& cs) {
  Mean air, disks, own_mach, cooler;
  int wedges = 0, unresolved = 0;
  std::map<std::pair<double, double>, double> beta_e1;  // (M, theta) at e = 1, default stream
  auto default_stream = [](const Json& r) {
    return std::abs(d(r, "granular_mach") - d(r, "mach")) < kSameValue &&
           std::abs(d(r, "packing") - 0.1) < kSameValue;
  };
  for (const auto& r : rows) {
    if (r.value("body", "") != "wedge") continue;
    ++wedges;
    if (!resolved(r)) {
      ++unresolved;
      continue;
    }
    own_mach.add(std::abs(d(r, "beta_deg") - d(r, "disk_gas_beta_deg")));
    if (default_stream(r) && std::abs(d(r, "restitution") - 1) < kSameValue) {
      air.add(d(r, "beta_deg") - d(r, "gas_beta_deg"));
      disks.add(d(r, "beta_deg") - d(r, "disk_gas_beta_deg"));
      beta_e1[{d(r, "mach"), d(r, "theta_deg")}] = d(r, "beta_deg");
    }
  }
  for (const auto& r : rows)
    if (r.value("body", "") == "wedge" && resolved(r) && default_stream(r) &&
        std::abs(d(r, "restitution") - 0.9) < kSameValue) {
      const auto it = beta_e1.find({d(r, "mach"), d(r, "theta_deg")});
      if (it != beta_e1.end()) cooler.add(it->second - d(r, "beta_deg"));
    }
  double e_lo = 2, e_hi = -1;
  for (const auto& c : cs)
    if (c.found) e_lo = std::min(e_lo, c.restitution), e_hi = std::max(e_hi, c.restitution);
  Mean ratio_e1, ratio_e09;
  for (const auto& r : rows)
    if (r.value("body", "") == "disc" && resolved(r)) {
      const double q = d(r, "standoff") / d(r, "billig_standoff");
      if (std::abs(d(r, "restitution") - 1) < kSameValue) ratio_e1.add(q);
      if (std::abs(d(r, "restitution") - 0.9) < kSameValue) ratio_e09.add(q);
    }
  std::ostringstream md;
  md << "## Reading\n\n"
     << "- Elastic disks (e = 1) behave as their own gas, not as air: over " << air.n
     << " resolved wedge shocks their angle lies " << fmt(air.value(), 2)
     << " deg above the gamma = 1.4 angle on average and " << fmt(disks.value(), 2)
     << " deg from the gamma = 2 angle; over every resolved wedge, the mean distance to the gamma "
        "= 2 "
     << "angle at the granular Mach number is " << fmt(own_mach.value(), 2) << " deg.\n"
     << "- Restitution moves the shock most: lowering e from 1 to 0.9 lowers the angle by "
     << fmt(cooler.value(), 2) << " deg on average (" << cooler.n
     << " pairs): inelastic collisions cool and compress the shocked layer.\n";
  if (e_hi > 0) {
    // Trend with Mach: mean crossing at the lowest and the highest Mach number.
    std::map<double, Mean> by_mach;
    for (const auto& c : cs)
      if (c.found) by_mach[c.mach].add(c.restitution);
    md << "- The granular angle equals air's at e between " << fmt(e_lo, 3) << " and "
       << fmt(e_hi, 3) << " (calibration surface below): on average "
       << fmt(by_mach.begin()->second.value(), 3) << " at M = " << fmt(by_mach.begin()->first)
       << " and " << fmt(by_mach.rbegin()->second.value(), 3)
       << " at M = " << fmt(by_mach.rbegin()->first) << ".\n";
  }
  // Continuum limit: disc series whose two largest resolved radii agree
  // within their combined 95% intervals.
  std::map<std::string, std::vector<Json>> disc_series;
  for (const auto& r : rows)
    if (r.value("body", "") == "disc")
      disc_series[fmt(d(r, "mach")) + "/" + fmt(d(r, "granular_mach")) + "/" +
                  fmt(d(r, "restitution")) + "/" + fmt(d(r, "packing"))]
          .push_back(r);
  int series_n = 0, series_flat = 0, series_unresolved = 0;
  for (auto& [k, rs] : disc_series) {
    std::vector<Json> ok;
    for (const auto& r : rs)
      if (resolved(r)) ok.push_back(r);
    std::sort(ok.begin(), ok.end(),
              [](const Json& a, const Json& b) { return d(a, "radius_d") < d(b, "radius_d"); });
    ++series_n;
    if (ok.size() < 2) {
      ++series_unresolved;
      continue;
    }
    const auto& a = ok[ok.size() - 2];
    const auto& b = ok.back();
    if (std::abs(d(a, "standoff") - d(b, "standoff")) <=
        std::hypot(d(a, "standoff_ci"), d(b, "standoff_ci")))
      ++series_flat;
  }
  md << "- Discs: the e = 1 standoff is " << fmt(ratio_e1.value(), 2)
     << " times Billig's (gamma = 1.4) on average, at e = 0.9 " << fmt(ratio_e09.value(), 2)
     << " times. Of " << series_n << " disc series, " << series_flat
     << " no longer change with radius between their two largest radii (continuum limit reached "
        "within the intervals), "
     << series_unresolved << " have fewer than two resolved standoffs.\n"
     << "- Resolution: " << unresolved << " of " << wedges
     << " wedge points have no resolved shock (none found, outside the wall-to-normal range or a "
        "95% "
        "half-width over 10 deg): at 3000 disks, near detachment and at the extremes of packing "
        "the "
        "small systems do not resolve the shock; they are tabulated but not compared.\n\n";
  return md.str();
}

std::string csv_of(const Json& rows) {
  const std::vector<const char*> cols{"key",
                                      "body",
                                      "mach",
                                      "granular_mach",
                                      "theta_deg",
                                      "radius_d",
                                      "restitution",
                                      "packing",
                                      "particles",
                                      "averaging",
                                      "status",
                                      "shock",
                                      "beta_deg",
                                      "beta_ci_deg",
                                      "gas_beta_deg",
                                      "disk_gas_beta_deg",
                                      "mach_angle_deg",
                                      "standoff",
                                      "standoff_ci",
                                      "billig_standoff",
                                      "cpu_seconds",
                                      "case_study",
                                      "calibration_training"};
  std::ostringstream os;
  for (std::size_t k = 0; k < cols.size(); ++k) os << (k ? "," : "") << cols[k];
  os << ",panels\n";
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < cols.size(); ++k) {
      os << (k ? "," : "");
      if (!r.contains(cols[k])) continue;
      const auto& v = r[cols[k]];
      if (v.is_string())
        os << v.get<std::string>();
      else if (v.is_boolean())
        os << (v.get<bool>() ? "true" : "false");
      else if (v.is_number())
        os << fmt(v.get<double>(), 6);
    }
    std::string ps;
    for (const auto& p : r["panels"]) {
      if (!ps.empty()) ps += ';';
      ps += p.get<std::string>();
    }
    os << "," << ps << "\n";
  }
  return os.str();
}

}  // namespace

std::vector<Crossing> calibration_crossings(const Json& rows) {
  // (theta, M) -> (e, beta, ci, gas) over the wedges at the gas's Mach and the default packing.
  std::map<std::pair<double, double>, std::vector<Json>> groups;
  for (const auto& r : rows)
    if (r.value("body", "") == "wedge" &&
        std::abs(d(r, "granular_mach") - d(r, "mach")) < kSameValue &&
        std::abs(d(r, "packing") - 0.1) < kSameValue && std::isfinite(d(r, "beta_deg")) &&
        resolved(r))
      groups[{d(r, "theta_deg"), d(r, "mach")}].push_back(r);
  std::vector<Crossing> out;
  for (auto& [tm, rs] : groups) {
    std::sort(rs.begin(), rs.end(), [](const Json& a, const Json& b) {
      return d(a, "restitution") < d(b, "restitution");
    });
    Crossing c;
    c.theta_deg = tm.first;
    c.mach = tm.second;
    if (rs.size() < 2) continue;  // one e value: no crossing to look for
    const double gas = d(rs.front(), "gas_beta_deg");
    for (std::size_t k = 0; k + 1 < rs.size() && !c.found; ++k) {
      const double e1 = d(rs[k], "restitution"), e2 = d(rs[k + 1], "restitution");
      const double b1 = d(rs[k], "beta_deg"), b2 = d(rs[k + 1], "beta_deg");
      if ((b1 - gas) * (b2 - gas) > 0 || b1 == b2) continue;
      // e* = e1 + t (e2 - e1), t = (gas - b1)/(b2 - b1); the 95% half-widths
      // of b1 and b2 propagated through t (independent runs).
      const double t = (gas - b1) / (b2 - b1);
      c.restitution = e1 + t * (e2 - e1);
      c.ci = std::abs(e2 - e1) / std::abs(b2 - b1) *
             std::hypot((1 - t) * d(rs[k], "beta_ci_deg"), t * d(rs[k + 1], "beta_ci_deg"));
      c.found = true;
    }
    if (!c.found) {
      const bool above = d(rs.front(), "beta_deg") > gas;
      c.note = std::string("no crossing: the granular angle is ") + (above ? "above" : "below") +
               " the gas's at every e from " + fmt(d(rs.front(), "restitution")) + " to " +
               fmt(d(rs.back(), "restitution"));
    }
    if (c.found && rs.front().value("case_study", false)) c.note = "case study: not training data";
    out.push_back(c);
  }
  return out;
}

// The e(M[, theta]) fit trained on this study's crossings, as
// `pipeline calibrate --from-points` makes it; its table goes to out_dir,
// never over the shipped one.
std::string training_section(const std::string& out_dir) {
  std::ostringstream md;
  md << "## Training the calibration on these points\n\n"
     << "`pipeline calibrate --from-points docs/figures/parametric/parametric_calibration.json --table FILE` "
        "fits e(M[, theta]) to the study's `crossings` (the case-study wedges M3/10, M4/15, M5/20 are left "
        "out, by the command as well as by the study) without running anything, with the same models and "
        "leave-one-out choice as `pipeline calibrate`. ";
  try {
    const Json fit = calibrate_from_points({out_dir + "/parametric_calibration.json"},
                                           out_dir + "/calibration_from_points.yaml");
    md << "On this study (" << fit["points"].get<std::size_t>() << " crossings) it chooses "
       << fit["model"].get<std::string>() << " (coefficients";
    for (const auto& c : fit["coefficients"]) md << " " << fmt(c.get<double>(), 3);
    md << "; leave-one-out RMS of e " << fmt(fit["loo_rms"].get<double>(), 2) << "). ";
  } catch (const std::exception& e) {
    md << "On this study no fit: " << e.what() << ". ";
  }
  md << "Those crossings are measured with the study's granular settings (fewer disks, shorter averaging "
        "than the scene defaults), and the e that matches air depends on the granular resolution, so such "
        "a table serves scenes run with the study's settings only; the shipped `pipeline/calibration.yaml` "
        "comes from `pipeline calibrate` at the defaults (docs/calibration.md).\n";
  return md.str();
}

void write_parametric_outputs(const Json& rows, const std::vector<ParametricPanel>& panels,
                              const Json& cost, const std::string& out_dir,
                              const std::string& figures_dir, const std::string& docs_page) {
  scene::make_dirs(figures_dir);
  const std::string csv = csv_of(rows);
  scene::write_file_atomic(out_dir + "/parametric.csv", csv);
  scene::write_json_atomic(out_dir + "/parametric.json", {{"cost", cost}, {"rows", rows}});
  const auto crossings = calibration_crossings(rows);
  Json training = Json::array(), surface = Json::array();
  for (const auto& r : rows)
    if (r.value("calibration_training", false))
      training.push_back({{"mach", r["mach"]},
                          {"angle_deg", r["theta_deg"]},
                          {"restitution", r["restitution"]},
                          {"granular_angle_deg", r["beta_deg"]},
                          {"granular_angle_ci_deg", r["beta_ci_deg"]},
                          {"gas_angle_deg", r["gas_beta_deg"]},
                          {"key", r["key"]}});
  for (const auto& c : crossings)
    if (c.found && c.note.empty())
      surface.push_back({{"mach", c.mach},
                         {"angle_deg", c.theta_deg},
                         {"restitution", c.restitution},
                         {"restitution_ci", c.ci}});
  const Json calib{
      {"gamma", kGammaAir},
      {"about",
       "Granular wedge shock angles for fitting e(M, theta): granular Mach = gas Mach, inflow "
       "packing 0.1, "
       "attached shocks; the wedge case studies M3/10, M4/15, M5/20 are left out of both lists."},
      {"points", training},
      {"crossings", surface}};
  scene::write_json_atomic(out_dir + "/parametric_calibration.json", calib);
  if (docs_page != "-") {
    scene::write_file_atomic(figures_dir + "/parametric.csv", csv);
    scene::write_json_atomic(figures_dir + "/parametric_calibration.json", calib);
  }

  std::ostringstream md;
  const fs::path page_dir =
      docs_page == "-" ? fs::path(out_dir) : fs::path(docs_page).parent_path();
  const std::string rel = fs::relative(figures_dir, page_dir).generic_string();
  std::size_t ok = 0, failed = 0, missing = 0;
  double point_cpu = 0;
  for (const auto& r : rows)
    if (std::isfinite(d(r, "cpu_seconds"))) point_cpu += d(r, "cpu_seconds");
  for (const auto& r : rows) {
    const auto st = r.value("status", "");
    (st == "ok" ? ok : st == "failed" ? failed : missing)++;
  }
  md << "# Parametric studies: where the granular analog tracks the gas\n\n"
     << "Written by `pipeline parametric` from its runs (do not edit by hand). Each point is one "
        "granular run "
        "(two replicas, seeds 1 and 2) and one shockfit; intervals are shockfit's 95% intervals "
        "(from the "
        "averaging groups' spread since 2026-12-05, a bootstrap over stations before). "
        "Wedges run with 3000 disks in the domain (the default is 9200) and 2 flow-through times "
        "of averaging "
        "(default 4), to fit the CPU budget; discs set their radius in particle diameters with "
        "`granular.body_diameters` (trial runs at M = 4 before this grid: shockfit found no "
        "standoff at R = 30, 40 and 45 d, one at 62 d). "
        "The gas references: the theta-beta-M relation for gamma = 1.4 (air, at the gas Mach "
        "number) and for "
        "gamma = 2 (dilute hard disks, at the granular Mach number), Billig's cylinder standoff "
        "(gamma = 1.4).\n\n"
     << "Size: " << rows.size() << " points (" << ok << " run, " << failed << " failed, " << missing
     << " not run); CPU " << fmt(point_cpu, 4) << " s summed over the points (granular + shockfit; "
     << fmt(cost.value("cpu_seconds", 0.0), 4)
     << " s in the invocation that wrote this page), estimate "
     << fmt(cost.value("estimate_cpu_seconds", 0.0), 4) << " s, budget "
     << fmt(cost.value("budget_cpu_seconds", 0.0), 4) << " s. Every point: [parametric.csv](" << rel
     << "/parametric.csv). Calibration training data: ["
     << "parametric_calibration.json](" << rel
     << "/parametric_calibration.json) (`points`: granular Mach = gas Mach, "
     << "packing 0.1, resolved, the case-study wedges M3/10, M4/15, M5/20 excluded; `crossings`: "
        "the surface below, "
        "the same exclusion).\n\n";
  md << reading(rows, crossings);
  for (const auto& panel : panels) {
    const std::string png = panel.id + ".png";
    md << "## " << panel.title << "\n\n![" << panel.id << "](" << rel << "/" << png << ")\n\n";
    if (panel.kind == "theta_beta")
      md << theta_beta_panel(panel, rows, figures_dir + "/" + png);
    else if (panel.kind == "standoff")
      md << standoff_panel(panel, rows, figures_dir + "/" + png);
    else
      md << mach_beta_panel(panel, rows, figures_dir + "/" + png);
    md << "\n";
  }
  md << "## Calibration surface: restitution at which the granular and gamma = 1.4 angles agree\n\n"
     << "![calibration_surface](" << rel << "/calibration_surface.png)\n\n"
     << "Linear interpolation in e between the two runs that bracket the gas angle; the 95% "
        "half-width propagates "
        "both runs' intervals.\n\n"
     << calibration_panel(crossings, figures_dir + "/calibration_surface.png") << "\n"
     << training_section(out_dir) << "\n";
  if (docs_page != "-") scene::write_file_atomic(docs_page, md.str());
  scene::write_file_atomic(out_dir + "/parametric.md", md.str());
}

}  // namespace pipeline
