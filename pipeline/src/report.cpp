#include "pipeline/report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "cfd/run_case.hpp"
#include "json_fields.hpp"
#include "pipeline/bow_shock_check.hpp"
#include "pipeline/figures.hpp"
#include "pipeline/one_scheme.hpp"
#include "pipeline/plot.hpp"
#include "scene/body.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/units.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {

// What ended the granular stage's averaging (summary `stopped_by`), in words.
std::string averaging_stop_words(const std::string& stopped_by) {
  if (stopped_by == "precision") return "precision: its interval met the target";
  if (stopped_by == "plateau") return "plateau: its interval stopped shrinking";
  if (stopped_by == "cost")
    return "cost: more averaging would have cost more CPU than its narrower band saves the finest "
           "clustered grid";
  if (stopped_by == "budget") return "budget: the next chunk would overrun granular.cpu_budget";
  if (stopped_by == "averaging") return "averaging: the time it was set to average";
  return stopped_by;
}

using scene::kDeg;
using scene::kNaN;
// Pixels across the CFD pictures: finer than the finest cells of the case
// studies (about 120 across the domain), so each cell shows at its size.
constexpr int kPictureWidthPx = 900;

nlohmann::json run_object(const GridRun& r, const Reference& ref) {
  nlohmann::json j = {{"cells", r.cells}, {"level", r.level}, {"cfd_wall_seconds", r.cfd_wall_seconds},
                      {"cpu_seconds", r.cfd_cpu_seconds}, {"mesh_cpu_seconds", r.mesh_cpu_seconds},
                      {"mesh_seconds", r.mesh_seconds}, {"steps", r.steps}, {"shock", r.shock},
                      {"steady_state_reached", r.steady}, {"error", r.error}, {"primary_error", r.primary_error},
                      {"primary_error_ci", r.primary_error_ci}};
  if (ref.quantity == "shock_angle_deg") {
    j["shock_angle_deg"] = r.value;
    j["shock_angle_ci_deg"] = r.value_ci;
    j["exact_shock_angle_deg"] = ref.value;
    j["error_deg"] = r.error;
    j["wall_pressure_ratio"] = r.wall_pressure_ratio;
    j["exact_pressure_ratio"] = ref.pressure_ratio;
    j["pressure_error"] = r.pressure_error;
  } else {
    j["standoff"] = r.value;
    j["standoff_ci"] = r.value_ci;
    j["reference_standoff"] = ref.value;
    j["reference_source"] = ref.source;
    j["relative_error"] = r.error;
  }
  return j;
}


std::string interval_text(const Interval& i) {
  if (!std::isfinite(i.value)) return "n/a";
  return format_number(i.value, 3) + "x (95%: " + format_number(i.ci_low, 3) + "-" + (std::isinf(i.ci_high) ? "inf" : format_number(i.ci_high, 3)) +
         ")";
}

std::string grid_name(const GridRun& r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_h%g", r.family.c_str(), r.level);
  return buf;
}
// The grid's case under cfd/ (older summaries name none: the grid's name).
std::string case_name(const GridRun& r) {
  return r.case_name.empty() ? grid_name(r) : r.case_name;
}

// Figures that could not be drawn are listed in the report, never dropped silently.
struct Warnings {
  std::vector<std::string> lines;
  void add(const std::string& what, const std::exception& e) { lines.push_back(what + ": " + e.what()); }
};

std::vector<scene::Vec2> accepted_points(const std::string& shock_csv, Warnings& w) {
  std::vector<scene::Vec2> pts;
  if (!fs::exists(shock_csv)) return pts;
  try {
    for (const auto& q : read_accepted_shock(shock_csv)) pts.push_back(q.point);
  } catch (const std::exception& e) {
    w.add("could not read " + shock_csv, e);
  }
  return pts;
}

void copy_if_exists(const std::string& from, const std::string& to) {
  std::error_code ec;
  if (fs::exists(from)) fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
}

// A family's fitted error-against-cost line over its cost range, with the
// band of the residual scatter (+-2 s in log error) as dashed lines. The fit
// is on the cost less `fixed` (the family's predictor on the total figure).
void add_fit(PlotSpec& p, const LogLogFit& f, const std::vector<double>& costs,
             const std::string& title, double fixed = 0) {
  if (!f.ok || costs.empty()) return;
  double lo = costs.front() - fixed, hi = costs.front() - fixed;
  for (const double c : costs) {
    lo = std::min(lo, c - fixed);
    hi = std::max(hi, c - fixed);
  }
  if (!(lo > 0)) return;
  constexpr int kPoints = 20;
  constexpr double kBandSd = 2.0;
  Series mid, up, down;
  mid.title = title + " fit (slope " + format_number(f.b, 2) + ")";
  up.title = title + " fit +-2 s";
  down.title = "";
  mid.style = "lines lw 2";
  up.style = down.style = "lines dt 2";
  for (int k = 0; k <= kPoints; ++k) {
    const double x = std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * k / kPoints);
    const double y = f.a + f.b * std::log(x);
    mid.x.push_back(x + fixed);
    mid.y.push_back(std::exp(y));
    up.x.push_back(x + fixed);
    up.y.push_back(std::exp(y + kBandSd * f.residual_sd));
    down.x.push_back(x + fixed);
    down.y.push_back(std::exp(y - kBandSd * f.residual_sd));
  }
  p.series.push_back(mid);
  p.series.push_back(up);
  p.series.push_back(down);
}

// Primary error against CPU cost: every run with its interval, each family's fit.
void cost_figures(const ReportInputs& in, const std::string& fig) {
  const auto& c = in.comparison;
  const auto& v = in.verdict;
  const std::string ylabel = v.primary.name + " (95% bars)";
  const std::string priced = v.priced ? " (priced: cells x steps at this run's fitted rate)" : "";
  PlotSpec cfd{"Primary error against CFD CPU time", "CFD CPU seconds to steady state" + priced, ylabel, true, true,
               {}, {}};
  PlotSpec tot{"Primary error against total CPU time (predictor + meshing + CFD)", "total CPU seconds" + priced,
               ylabel, true, true, {}, {}};
  for (const auto* fam : {&c.uniform, &c.clustered}) {
    const bool clustered = fam == &c.clustered;
    const std::string title = clustered ? "clustered (" + in.prediction.predictor + ")" : "uniform";
    Series sc, st;
    sc.title = st.title = title;
    std::vector<double> xc, xt;
    for (const auto& r : *fam) {
      if (!(r.primary_error > 0) || !(r.cfd_cpu_seconds > 0)) continue;
      const double cfd_cpu = verdict_cfd_cpu(v, r.cells, r.steps, r.cfd_cpu_seconds);
      const double total = cfd_cpu + verdict_mesh_cpu(v, r.cells, r.steps, r.mesh_cpu_seconds) +
                           (clustered ? v.predictor_cpu : 0.0);
      sc.x.push_back(cfd_cpu);
      st.x.push_back(total);
      for (auto* s : {&sc, &st}) {
        s->y.push_back(r.primary_error);
        s->yerr.push_back(std::isfinite(r.primary_error_ci) ? r.primary_error_ci : 0.0);
      }
      xc.push_back(cfd_cpu);
      xt.push_back(total);
    }
    cfd.series.push_back(sc);
    tot.series.push_back(st);
    const FamilyFitInfo& info = clustered ? v.clustered : v.uniform;
    add_fit(cfd, info.cfd, xc, title);
    add_fit(tot, info.total, xt, title, clustered ? v.predictor_cpu : 0.0);
  }
  plot_png(cfd, fig + "/error_vs_cfd_cpu.png");
  plot_png(tot, fig + "/error_vs_total_cpu.png");
  PlotSpec ec{"Primary error against cells", "cells", ylabel, true, true, {}, {}};
  for (const auto* fam : {&c.uniform, &c.clustered}) {
    Series s;
    s.title = fam == &c.uniform ? "uniform" : "clustered at the predicted shock";
    for (const auto& r : *fam) {
      if (!(r.primary_error > 0)) continue;
      s.x.push_back(static_cast<double>(r.cells));
      s.y.push_back(r.primary_error);
    }
    ec.series.push_back(s);
  }
  plot_png(ec, fig + "/error_vs_cells.png");
}

void field_figures(const ReportInputs& in, const std::string& fig, Warnings& w) {
  const std::string dir = in.out_dir;
  const auto& c = in.comparison;
  const bool angle = in.reference.quantity == "shock_angle_deg";
  const auto& granular_pts = in.prediction.curve;  // the curve meshgen was given
  const std::string predicted = "predicted (" + in.prediction.predictor + ")";
  // The granular stations as shockfit fitted them (an attached shock is
  // meshed round the apex ray at their angle instead).
  const bool granular = in.prediction.predictor == "granular";
  const std::vector<scene::Vec2> stations =
      granular ? accepted_points(dir + "/shockfit/shock.csv", w) : std::vector<scene::Vec2>{};
  std::vector<scene::Vec2> cfd_pts;
  std::string cfd_name;
  if (c.clustered_pick >= 0) {
    cfd_name = case_name(c.clustered[c.clustered_pick]);
    cfd_pts = accepted_points(dir + "/cfd/" + cfd_name + "/shockfit/shock.csv", w);
  }
  std::vector<scene::Vec2> exact;
  if (angle) {
    const double b = in.reference.value * kDeg;
    const auto d = scene::scene_domain(in.scene);
    for (int k = 0; k <= 20; ++k) {
      const double x = d.xmax * k / 20.0;
      if (x * std::tan(b) <= d.ymax) exact.push_back({x, x * std::tan(b)});
    }
  }
  const std::string gvti = dir + "/granular/fields.vti";
  if (granular && fs::exists(gvti)) {
    try {
      const auto lat = scene::read_vti(gvti);
      field_png(lat, "volume_fraction", "Granular volume fraction with the fitted shock",
                {{"granular shock", stations, "points pt 7 ps 0.8 lc rgb 'white'"}},
                fig + "/granular_volume_fraction.png");
      field_png(lat, "u", "Granular velocity u", {{"granular shock", stations, "points pt 7 ps 0.8 lc rgb 'white'"}},
                fig + "/granular_velocity.png");
    } catch (const std::exception& e) {
      w.add("granular figures skipped", e);
    }
  }
  if (!cfd_name.empty()) {
    try {
      const auto lat = scene::read_vti(dir + "/cfd/" + cfd_name + "/fields.vti");
      field_png(lat, "mach", "Shocks over the clustered CFD Mach field: predicted, CFD and exact",
                {{predicted, granular_pts, "points pt 7 ps 1.0 lc rgb 'white'"},
                 // Beside the ray they stand off; otherwise they are the curve above.
                 {"granular stations", in.prediction.kind == scene::ShockKind::attached ? stations
                                                                                       : std::vector<scene::Vec2>{},
                  "points pt 6 ps 0.8 lc rgb 'gray'"},
                 {"CFD (clustered)", cfd_pts, "points pt 4 ps 0.8 lc rgb 'black'"},
                 {"exact", exact, "lines lw 2 dt 2 lc rgb 'magenta'"}},
                fig + "/shocks_compared.png");
    } catch (const std::exception& e) {
      w.add("shock comparison figure skipped", e);
    }
  }
  const auto domain = scene::scene_domain(in.scene);
  const int picture_height =
      std::clamp(static_cast<int>(std::lround(kPictureWidthPx * domain.height() / domain.width())), 100, kPictureWidthPx);
  for (const auto* fam : {&c.uniform, &c.clustered}) {
    for (const auto& r : *fam) {
      const std::string name = grid_name(r);
      const std::string case_dir = dir + "/cfd/" + case_name(r);
      if (fs::exists(case_dir + "/constant/polyMesh")) {
        try {
          // Drawn from the CFD cells themselves: every pixel takes the value
          // of the cell that contains it, at a resolution finer than the cells.
          const auto lat = cfd::resample_to_lattice(in.scene, case_dir, kPictureWidthPx, picture_height);
          field_png(lat, "mach", "CFD Mach number, " + name + " (cell values)",
                    {{"CFD shock", accepted_points(case_dir + "/shockfit/shock.csv", w),
                      "points pt 7 ps 0.6 lc rgb 'white'"}},
                    fig + "/cfd_mach_" + name + ".png");
        } catch (const std::exception& e) {
          w.add("Mach figure of " + name + " skipped", e);
        }
      }
      for (const char* f : {"history.png", "convergence.png"})
        copy_if_exists(case_dir + "/" + f, fig + "/cfd_" + name + "_" + f);
      for (const char* f : {"mesh.png", "mesh_zoom.png"})
        copy_if_exists(dir + "/meshgen/" + (r.mesh_name.empty() ? name : r.mesh_name) + "/" + f,
                       fig + "/mesh_" + name + "_" + f);
    }
  }
}

void verdict_section(std::ostringstream& md, const ReportInputs& in) {
  const auto& v = in.verdict;
  md << "## Verdict\n\n";
  md << "Primary error: **" << v.primary.name << "** against the " << v.primary.reference << " — "
     << v.primary.why << ".\n\n";
  if (std::isfinite(v.speedup_total.value)) {
    if (std::isfinite(v.beyond_uniform.error))
      md << "The clustered family's finest error (" << format_number(v.beyond_uniform.error, 3)
         << ") lies below every uniform grid's, so the speedup is read at the uniform finest's "
            "error ("
         << format_number(v.target_error, 3) << "), inside both families' ranges";
    else
      md << "At the clustered family's finest error (" << format_number(v.target_error, 3) << ")";
    md << ", reading each family's log-log fit of error against CPU time:\n\n"
       << "- CFD CPU time: uniform / clustered = **" << interval_text(v.speedup_cfd) << "** — "
       << v.verdict_cfd << ";\n- total CPU time (predictor " << format_number(v.predictor_cpu, 3)
       << " s, meshing and CFD): **" << interval_text(v.speedup_total) << "** — **" << v.verdict
       << "**.\n\n";
    if (std::isfinite(v.beyond_uniform.error))
      md << "At the clustered finest error itself, extrapolating the uniform fit past its finest "
            "grid: CFD "
         << interval_text(v.beyond_uniform.speedup_cfd) << ", total "
         << interval_text(v.beyond_uniform.speedup_total) << " (a bound, not a measurement).\n\n";
    md << "\"not distinguishable\" means the 95% interval contains 1.";
    if (!v.note.empty()) md << " Note: " << v.note << ".";
    md << "\n\n";
    if (std::isfinite(v.calibration.cpu_seconds)) {
      const auto& k = v.calibration;
      md << "Calibration, a separate line: the restitution table cost " << format_number(k.cpu_seconds, 3)
         << " CPU s once and serves every scene (" << format_number(k.cpu_seconds / std::max(1, k.scenes_served), 3)
         << " s each over the " << k.scenes_served << " case studies; not in the totals above). Charged to this "
            "scene alone, the total speedup would be " << interval_text(k.speedup_total_if_alone) << " — "
         << k.verdict_if_alone << ".\n\n";
    }
    if (v.priced) {
      const WorkPrice& p = v.price;
      md << "Costs are **priced**: each grid's cells and solver steps (the same on every run) at this run's fitted "
            "rate, " << format_number(p.per_cell_step * 1e6, 3) << " us per cell-step + "
         << format_number(p.per_step * 1e3, 3) << " ms per step, meshing " << format_number(p.mesh_base, 3) << " s + "
         << format_number(p.mesh_per_cell * 1e6, 3) << " us per cell (fitted on " << p.runs
         << " runs); one timing scatters by " << format_number(100 * p.cfd_log_sd, 2)
         << "% (log sd) about it, which the interval carries with the predictor's timing. On the measured single "
            "timings instead: total " << interval_text(v.measured_total) << " — " << verdict_of(v.measured_total)
         << ".\n\n";
    }
  } else {
    md << "No verdict: " << (v.note.empty() ? "missing runs" : v.note) << " (see the table).\n\n";
  }
  for (const auto* f : {&v.uniform, &v.clustered})
    for (const auto& e : f->excluded) md << "- excluded from the fit: " << e << "\n";
  md << "\n";
  const auto& c = in.comparison;
  if (std::isfinite(c.speedup_cfd))
    md << "Secondary (the shock angle or standoff, wall seconds, interpolated): " << format_number(c.speedup_cfd, 3)
       << "x in CFD wall time.\n\n";
  else if (std::isfinite(c.speedup_bound))
    md << "Secondary (the shock angle or standoff, wall seconds): no uniform grid reached the clustered grid's "
          "error; against the finest uniform grid, at least " << format_number(c.speedup_bound, 3) << "x in CFD wall time.\n\n";
}

void runs_table(std::ostringstream& md, const ReportInputs& in) {
  const auto& c = in.comparison;
  const bool angle = in.reference.quantity == "shock_angle_deg";
  md << "## Runs\n\n| family | h / h_min | cells | CFD CPU s | CFD wall s | mesh CPU s | steps | us/cell-step | "
        "steady | " << in.verdict.primary.name << " | "
     << (angle ? "angle (deg)" : "standoff") << " | error | "
     << (angle ? "p2/p1 (exact " + format_number(in.reference.pressure_ratio, 4) + ")" : "p0/p_inf") << " |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto* fam : {&c.uniform, &c.clustered})
    for (const auto& r : *fam)
      md << "| " << r.family << " | " << r.level << " | " << r.cells << " | " << format_number(r.cfd_cpu_seconds) << " | "
         << format_number(r.cfd_wall_seconds) << " | " << format_number(r.mesh_cpu_seconds) << " | " << r.steps << " | "
         << format_number(r.cpu_us_per_cell_step(), 2) << " | " << (r.steady ? "yes" : "**no**") << " | "
         << format_number(r.primary_error, 3) << " ± " << format_number(r.primary_error_ci, 2) << " | " << format_number(r.value, 4) << " ± "
         << format_number(r.value_ci, 2) << " | " << format_number(r.error) << " | "
         << (angle ? format_number(r.wall_pressure_ratio, 4) : format_number(r.stagnation_pressure_ratio, 4)) << " |\n";
  md << "\n";
  const std::string su = family_scheme(c.uniform), sc = family_scheme(c.clustered);
  if (su.empty() && sc.empty()) return;
  md << "Schemes (flux/limiter): uniform " << (su.empty() ? "n/a" : su) << ", clustered "
     << (sc.empty() ? "n/a" : sc) << ".";
  if (su.rfind("mixed", 0) == 0 || sc.rfind("mixed", 0) == 0)
    md << " **A family mixes schemes: its errors mix their truncation errors (see the warnings).**";
  else if (!su.empty() && !sc.empty() && su != sc)
    md << " The families ran different schemes: each kept the most accurate one that held on all "
          "its grids, so the comparison prices the more dissipative one where a family needed it.";
  md << "\n\n";
}

// Richardson estimates from the independent reference grid (blunt bodies).
void convergence_section(std::ostringstream& md, const nlohmann::json& g) {
  if (!g.is_object()) return;
  md << "## Grid convergence (independent reference grid)\n\n";
  const auto& ref = g["reference_run"];
  md << "Reference grid: uniform, h = " << format_number(ref.value("level", kNaN), 3) << " h_min, "
     << ref.value("cells", 0L) << " cells, CPU " << format_number(ref.value("cpu_seconds", kNaN), 4) << " s, steady "
     << (ref.value("steady_state_reached", false) ? "yes" : "**no**") << " (a member of neither family).\n\n";
  if (g.contains("scheme_note")) md << "**Note:** " << g.value("scheme_note", "") << ".\n\n";
  if (g.contains("note")) {
    md << g.value("note", "") << ".\n\n";
    return;
  }
  md << "| quantity | observed order | Richardson estimate | GCI (fine) | note |\n|---|---|---|---|---|\n";
  for (const char* q : {"standoff", "drag_coefficient", "stagnation_pressure_ratio"}) {
    const auto& c = g[q];
    auto num = [&](const char* k) { return c.contains(k) && c[k].is_number() ? c[k].get<double>() : kNaN; };
    md << "| " << q << " | " << format_number(num("observed_order"), 3) << " | " << format_number(num("extrapolated"), 5) << " | "
       << format_number(num("gci_fine"), 3) << " | " << c.value("note", "") << " |\n";
  }
  md << "\nRichardson triple: the reference grid and the uniform grids 2x and 4x coarser (Roache; safety factor "
        "1.25). The stagnation pressure's exact value is Rayleigh's; its row checks the extrapolation.\n\n";
}

}  // namespace

nlohmann::json make_summary(const ReportInputs& in) {
  const auto& c = in.comparison;
  const auto& ref = in.reference;
  nlohmann::json j;
  j["scene"] = in.scene.name;
  j["reference"] = {{"quantity", ref.quantity}, {"source", ref.source}, {"value", ref.value},
                    {"pressure_ratio", ref.pressure_ratio}};
  j["clustered"] = c.clustered_pick >= 0 ? run_object(c.clustered[c.clustered_pick], ref) : nlohmann::json(nullptr);
  j["uniform"] = c.uniform_pick >= 0 ? run_object(c.uniform[c.uniform_pick], ref) : nlohmann::json(nullptr);
  if (c.uniform_pick >= 0) j["uniform"]["as_accurate_as_clustered"] = c.uniform_matches;
  const Prediction& p = in.prediction;
  nlohmann::json g = p.summary();
  g["wall_seconds"] = p.wall_seconds;
  if (p.predictor == "granular") g["restitution"] = in.scene.granular.restitution;
  if (ref.quantity == "shock_angle_deg") {
    g["error_deg"] = std::abs(p.shock_angle_deg - ref.value);
  } else {
    g["relative_error"] = std::abs(p.standoff - ref.value) / ref.value;
  }
  j["prediction"] = g;
  j["granular"] = g;  // the older key, kept for scripts
  j["predictor"] = p.predictor;
  const auto& v = in.verdict;
  j["primary_error"] = v.primary.name;
  j["speedup_cfd"] = interval_json(v.speedup_cfd);
  j["speedup_total"] = interval_json(v.speedup_total);
  j["verdict"] = v.verdict;
  j["verdict_details"] = verdict_json(v);
  j["speedup_cfd_at_equal_error"] = c.speedup_cfd;
  j["speedup_total_at_equal_error"] = c.speedup_total;
  j["speedup_lower_bound"] = c.speedup_bound;
  j["speedup_total_lower_bound"] = c.speedup_total_bound;
  j["calibration"] = in.calibration_note.empty() ? nlohmann::json(nullptr) : nlohmann::json(in.calibration_note);
  j["total_wall_seconds"] = in.total_seconds;
  j["grid_convergence"] = in.grid_convergence;
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : c.uniform) runs.push_back(r.to_json());
  for (const auto& r : c.clustered) runs.push_back(r.to_json());
  j["runs"] = runs;
  j["schemes"] = {{"uniform", family_scheme(c.uniform)}, {"clustered", family_scheme(c.clustered)}};
  return j;
}

std::string verdict_line(const nlohmann::json& summary) {
  auto num = [](const nlohmann::json& o, const char* k) {
    return o.contains(k) && o[k].is_number() ? o[k].get<double>() : kNaN;
  };
  const auto& t = summary["speedup_total"];
  const auto& c = summary["speedup_cfd"];
  std::ostringstream os;
  // An unbounded interval end is written as null in JSON.
  auto hi = [&](const nlohmann::json& o) {
    return o.contains("ci_high") && o["ci_high"].is_null() && std::isfinite(num(o, "value"))
               ? std::numeric_limits<double>::infinity()
               : num(o, "ci_high");
  };
  os << summary.value("scene", "") << ": " << summary.value("verdict", "not distinguishable") << " — total CPU "
     << interval_text({num(t, "value"), num(t, "ci_low"), hi(t)}) << ", CFD CPU "
     << interval_text({num(c, "value"), num(c, "ci_low"), hi(c)}) << " at equal "
     << summary.value("primary_error", "error");
  return os.str();
}

void write_report(const ReportInputs& in, const nlohmann::json& summary, const std::string& file_name) {
  const std::string dir = in.out_dir;
  const std::string fig = dir + "/figures";
  fs::create_directories(fig);
  const auto& c = in.comparison;
  const auto& ref = in.reference;
  const bool angle = ref.quantity == "shock_angle_deg";
  Warnings warnings;
  cost_figures(in, fig);
  field_figures(in, fig, warnings);

  std::ostringstream md;
  md << "# " << in.scene.name << ": grid clustered at the " << in.prediction.predictor
     << " prediction against uniform grids\n\n";
  md << "Generated by `pipeline run`. Costs are CPU seconds (user + system, solver ranks and "
        "meshing tools included; wall seconds beside them), one run per grid; the intervals come from the "
        "families' fits. Shock reference: "
     << ref.source << " ("
     << (angle ? "shock angle " + format_number(ref.value, 4) + " deg" : "standoff " + format_number(ref.value, 4) + " body lengths")
     << ").\n\n";
  if (!in.calibration_note.empty()) md << "Calibration: " << in.calibration_note << ".\n\n";
  verdict_section(md, in);
  const auto& g = summary["prediction"];
  md << "Prediction (" << in.prediction.predictor << "): shock " << g.value("shock", "none") << ", ";
  // A predictor that located no shock (adapt still sizes its grids) leaves these null.
  if (angle) md << "angle " << format_number(number_or_nan(g, "shock_angle_deg"), 4) << " deg (error " << format_number(number_or_nan(g, "error_deg"), 3) << " deg)";
  else md << "standoff " << format_number(number_or_nan(g, "standoff"), 4) << " (relative error " << format_number(number_or_nan(g, "relative_error"), 3) << ")";
  md << ", CPU " << format_number(number_or_nan(g, "cpu_seconds"), 3) << " s (wall " << format_number(number_or_nan(g, "wall_seconds"), 3)
     << " s).";
  const nlohmann::json details = g.value("details", nlohmann::json::object());
  const double band = number_or_nan(details, "band_angle_half_width_deg");
  const double scatter = number_or_nan(details, "calibration_angle_scatter_deg");
  if (in.prediction.kind == scene::ShockKind::attached && std::isfinite(band))
    md << " Meshed as the ray from the apex at that angle, its band +-" << format_number(band, 3) << " deg"
       << (std::isfinite(scatter) ? " (the angle's own 95% interval +-" + format_number(number_or_nan(g, "shock_angle_ci_deg"), 3) +
                                        " deg combined with 1.96 times the calibration table's own error (its out-of-sample RMS less the left-out runs' noise), " +
                                        format_number(scatter, 3) + " deg)"
                                  : " (the angle's own 95% interval; the scene sets its restitution, so no calibration scatter)")
       << ".";
  const nlohmann::json averaging = details.value("averaging", nlohmann::json::object());
  if (in.prediction.predictor == "granular" && averaging.is_object() &&
      std::isfinite(number_or_nan(averaging, "flow_throughs"))) {
    auto text = [&](const char* key) {
      const auto it = averaging.find(key);
      return it != averaging.end() && it->is_string() ? it->get<std::string>() : std::string();
    };
    md << " The granular stage averaged "
       << format_number(number_or_nan(averaging, "flow_throughs"), 3)
       << " flow-through times (stopped by " << averaging_stop_words(text("stopped_by"))
       << (text("target_source").empty() ? std::string() : "; target " + text("target_source"))
       << ").";
  }
  const double bow = number_or_nan(details, "calibration_bow_shock_relative_rms");
  if (in.prediction.kind == scene::ShockKind::detached && in.prediction.predictor == "granular")
    md << (std::isfinite(bow) ? " Its band at each station: the station's 95% interval combined with 1.96 times the "
                                "calibration's out-of-sample relative error of bow-shock distances (" +
                                    format_number(bow, 3) + " RMS) times the station's distance."
                              : " Its band: the stations' own 95% intervals (no bow-shock scatter in the calibration, "
                                "or the scene sets its restitution).");
  if (angle && std::abs(number_or_nan(g, "error_deg")) > 1.0)
    md << " **The predicted shock is off the exact shock by more than 1 deg: the clustered band may miss part of the CFD shock.**";
  md << "\n\n";
  runs_table(md, in);
  convergence_section(md, in.grid_convergence);
  for (const auto* fam : {&c.uniform, &c.clustered})
    for (const auto& r : *fam) {
      if (!r.note.empty()) warnings.lines.push_back(grid_name(r) + ": " + r.note);
      if (r.shock_axis_deviation_cells > kCarbuncleCells)
        warnings.lines.push_back(grid_name(r) + ": the bow shock strays " + format_number(r.shock_axis_deviation_cells, 2) +
                                 " cells from its smooth shape at the symmetry axis (a carbuncle is suspected; over " +
                                 format_number(kCarbuncleCells, 2) +
                                 " cells): its stagnation pressure reads a damaged stagnation streamline");
    }
  if (!warnings.lines.empty()) {
    md << "## Warnings\n\n";
    for (const auto& l : warnings.lines) md << "- " << l << "\n";
    md << "\n";
  }
  md << "## Figures\n\n";
  auto img = [&](const std::string& file, const std::string& caption) {
    if (fs::exists(fig + "/" + file)) md << "![" << caption << "](figures/" << file << ")\n\n*" << caption << "*\n\n";
  };
  img("error_vs_total_cpu.png", "Primary error against total CPU time, with each family's fit");
  img("error_vs_cfd_cpu.png", "Primary error against CFD CPU time, with each family's fit");
  img("error_vs_cells.png", "Primary error against cells");
  img("granular_volume_fraction.png", "Granular volume fraction with the fitted shock");
  img("granular_velocity.png", "Granular velocity u");
  img("shocks_compared.png", "Predicted, CFD and exact shocks");
  for (const auto* fam : {&c.uniform, &c.clustered})
    for (const auto& r : *fam) {
      const std::string buf = grid_name(r);
      img("mesh_" + buf + "_mesh.png", "Grid " + buf);
      img("cfd_" + buf + "_history.png", "Convergence history " + buf);
      img("cfd_" + buf + "_convergence.png", "Convergence history " + buf);
      img("cfd_mach_" + buf + ".png", "CFD Mach number " + buf);
    }
  md << "Errors are against the references named above; ± on the primary error is its change over the last write "
        "interval (the steady state's flicker), ± on the shock is the 95% interval of the shock located on the CFD "
        "solution.\n\n";
  md << "Total pipeline wall time: " << format_number(in.total_seconds, 4) << " s (cached stages cost nothing).\n";
  scene::write_file_atomic(dir + "/" + file_name, md.str());
}

}  // namespace pipeline
