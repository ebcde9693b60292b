#include "pipeline/report.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "pipeline/figures.hpp"
#include "pipeline/plot.hpp"
#include "scene/body.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "shockfit/locate.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = std::numbers::pi / 180.0;

nlohmann::json run_object(const GridRun& r, const Reference& ref) {
  nlohmann::json j = {{"cells", r.cells}, {"level", r.level}, {"cfd_wall_seconds", r.cfd_wall_seconds},
                      {"mesh_seconds", r.mesh_seconds}, {"steps", r.steps}, {"shock", r.shock},
                      {"steady_state_reached", r.steady}, {"error", r.error}};
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

std::string fmt(double v, int prec = 3) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream os;
  os.precision(prec);
  os << v;
  return os.str();
}

std::vector<scene::Vec2> accepted_points(const std::string& shock_csv) {
  std::vector<scene::Vec2> pts;
  try {
    for (const auto& st : shockfit::read_shock_csv(shock_csv))
      if (st.accepted) pts.push_back(st.shock);
  } catch (const std::exception&) {
  }
  return pts;
}

void copy_if_exists(const std::string& from, const std::string& to) {
  std::error_code ec;
  if (fs::exists(from)) fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
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
  const auto& p = in.prediction;
  nlohmann::json g = {{"shock", p.value("shock", "none")}, {"wall_seconds", p.value("granular_wall_seconds", kNaN)},
                      {"restitution", in.scene.granular.restitution}};
  if (ref.quantity == "shock_angle_deg") {
    const double a = p.contains("shock_angle_deg") && p["shock_angle_deg"].is_number() ? p["shock_angle_deg"].get<double>() : kNaN;
    g["shock_angle_deg"] = a;
    g["shock_angle_ci_deg"] = p.value("shock_angle_ci_deg", nlohmann::json(nullptr));
    g["error_deg"] = std::abs(a - ref.value);
  } else {
    const double sd = p.contains("standoff") && p["standoff"].is_number() ? p["standoff"].get<double>() : kNaN;
    g["standoff"] = sd;
    g["standoff_ci"] = p.value("standoff_ci", nlohmann::json(nullptr));
    g["relative_error"] = std::abs(sd - ref.value) / ref.value;
  }
  j["granular"] = g;
  j["speedup_cfd_at_equal_error"] = c.speedup_cfd;
  j["speedup_total_at_equal_error"] = c.speedup_total;
  j["speedup_lower_bound"] = c.speedup_bound;
  j["speedup_total_lower_bound"] = c.speedup_total_bound;
  j["calibration"] = in.calibration_note.empty() ? nlohmann::json(nullptr) : nlohmann::json(in.calibration_note);
  j["total_wall_seconds"] = in.total_seconds;
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : c.uniform) runs.push_back(r.to_json());
  for (const auto& r : c.clustered) runs.push_back(r.to_json());
  j["runs"] = runs;
  return j;
}

void write_report(const ReportInputs& in, const nlohmann::json& summary) {
  const std::string dir = in.out_dir;
  const std::string fig = dir + "/figures";
  fs::create_directories(fig);
  const auto& c = in.comparison;
  const auto& ref = in.reference;
  const bool angle = ref.quantity == "shock_angle_deg";
  const std::string qlabel = angle ? "shock angle error (deg)" : "relative standoff error";

  // Error against CFD wall time and against cells, both families.
  PlotSpec et{"Error against CFD wall time", "CFD wall time to steady state (s)", qlabel, true, true, {}, {}};
  PlotSpec ec{"Error against cells", "cells", qlabel, true, true, {}, {}};
  for (const auto* fam : {&c.uniform, &c.clustered}) {
    Series st, sc;
    st.title = sc.title = fam == &c.uniform ? "uniform" : "clustered at the granular shock";
    for (const auto& r : *fam) {
      if (!std::isfinite(r.error) || r.error <= 0) continue;
      st.x.push_back(r.cfd_wall_seconds);
      st.y.push_back(r.error);
      sc.x.push_back(static_cast<double>(r.cells));
      sc.y.push_back(r.error);
    }
    et.series.push_back(st);
    ec.series.push_back(sc);
  }
  plot_png(et, fig + "/error_vs_time.png");
  plot_png(ec, fig + "/error_vs_cells.png");

  // Granular fields with the fitted shock; granular, CFD and exact shocks on one plot.
  const std::string gdir = dir + "/granular", sdir = dir + "/shockfit";
  const auto granular_pts = accepted_points(sdir + "/shock.csv");
  std::vector<scene::Vec2> cfd_pts;
  std::string cfd_name;
  if (c.clustered_pick >= 0) {
    const auto& r = c.clustered[c.clustered_pick];
    char buf[64];
    std::snprintf(buf, sizeof buf, "clustered_h%g", r.level);
    cfd_name = buf;
    cfd_pts = accepted_points(dir + "/cfd/" + cfd_name + "/shockfit/shock.csv");
  }
  std::vector<scene::Vec2> exact;
  if (angle) {
    const double b = ref.value * kDeg;
    const auto d = scene::scene_domain(in.scene);
    for (int k = 0; k <= 20; ++k) {
      const double x = d.xmax * k / 20.0;
      if (x * std::tan(b) <= d.ymax) exact.push_back({x, x * std::tan(b)});
    }
  }
  try {
    const auto lat = scene::read_vti(gdir + "/fields.vti");
    field_png(lat, "volume_fraction", "Granular volume fraction with the fitted shock",
              {{"granular shock", granular_pts, "points pt 7 ps 0.8 lc rgb 'white'"}}, fig + "/granular_volume_fraction.png");
    field_png(lat, "u", "Granular velocity u", {{"granular shock", granular_pts, "points pt 7 ps 0.8 lc rgb 'white'"}},
              fig + "/granular_velocity.png");
  } catch (const std::exception&) {
  }
  // The three shocks over the clustered CFD solution's Mach field.
  try {
    const auto lat = scene::read_vti(dir + "/cfd/" + cfd_name + "/fields.vti");
    field_png(lat, "mach", "Shocks over the clustered CFD Mach field: granular, CFD and exact",
              {{"granular", granular_pts, "points pt 7 ps 1.0 lc rgb 'white'"},
               {"CFD (clustered)", cfd_pts, "points pt 4 ps 0.8 lc rgb 'black'"},
               {"exact", exact, "lines lw 2 dt 2 lc rgb 'magenta'"}},
              fig + "/shocks_compared.png");
  } catch (const std::exception&) {
  }
  // Mach field of each CFD solution.
  for (const auto* fam : {&c.uniform, &c.clustered}) {
    for (const auto& r : *fam) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s_h%g", r.family.c_str(), r.level);
      try {
        const auto lat = scene::read_vti(dir + "/cfd/" + buf + "/fields.vti");
        field_png(lat, "mach", std::string("CFD Mach number, ") + buf,
                  {{"CFD shock", accepted_points(dir + "/cfd/" + buf + "/shockfit/shock.csv"), "points pt 7 ps 0.6 lc rgb 'white'"}},
                  fig + "/cfd_mach_" + buf + ".png");
      } catch (const std::exception&) {
      }
      for (const char* f : {"history.png", "convergence.png"})
        copy_if_exists(dir + "/cfd/" + buf + "/" + f, fig + "/cfd_" + std::string(buf) + "_" + f);
      for (const char* f : {"mesh.png", "mesh_zoom.png"})
        copy_if_exists(dir + "/meshgen/" + buf + "/" + f, fig + "/mesh_" + std::string(buf) + "_" + f);
    }
  }

  std::ostringstream md;
  md << "# " << in.scene.name << ": granular-predicted grid against uniform grids\n\n";
  md << "Generated by `pipeline run`. Reference: " << ref.source << " ("
     << (angle ? "shock angle " + fmt(ref.value, 4) + " deg" : "standoff " + fmt(ref.value, 4) + " body lengths") << ").\n\n";
  if (!in.calibration_note.empty()) md << "Calibration: " << in.calibration_note << ".\n\n";
  md << "## Verdict\n\n";
  if (std::isfinite(c.speedup_cfd)) {
    md << "At equal error the clustered grid reaches steady state **" << fmt(c.speedup_cfd, 3)
       << "x** faster in CFD wall time than the uniform family (interpolated), and **" << fmt(c.speedup_total, 3)
       << "x** faster including the granular stage and meshing.\n\n";
  } else if (std::isfinite(c.speedup_bound)) {
    md << "No uniform grid of the series reached the clustered grid's error; against the finest uniform grid the "
          "clustered grid is at least **" << fmt(c.speedup_bound, 3) << "x** faster in CFD wall time, and at least **"
       << fmt(c.speedup_total_bound, 3) << "x** including the granular stage and meshing.\n\n";
  } else {
    md << "No speedup could be computed (missing runs or errors; see the table).\n\n";
  }
  const auto& g = summary["granular"];
  md << "Granular prediction: shock " << g.value("shock", "none") << ", ";
  if (angle) md << "angle " << fmt(g.value("shock_angle_deg", kNaN), 4) << " deg (error " << fmt(g.value("error_deg", kNaN), 3) << " deg)";
  else md << "standoff " << fmt(g.value("standoff", kNaN), 4) << " (relative error " << fmt(g.value("relative_error", kNaN), 3) << ")";
  md << ", granular wall time " << fmt(g.value("wall_seconds", kNaN), 3) << " s.";
  if (angle && std::abs(g.value("error_deg", 0.0)) > 1.0)
    md << " **The granular shock is off the exact shock by more than 1 deg: the clustered band may miss part of the CFD shock.**";
  md << "\n\n## Runs\n\n| family | h / h_min | cells | CFD wall s | steps | steady | " << (angle ? "angle (deg)" : "standoff")
     << " | error | " << (angle ? "p2/p1 (exact " + fmt(ref.pressure_ratio, 4) + ")" : "")
     << " | speedup at equal error |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto* fam : {&c.uniform, &c.clustered})
    for (const auto& r : *fam)
      md << "| " << r.family << " | " << r.level << " | " << r.cells << " | " << fmt(r.cfd_wall_seconds) << " | " << r.steps
         << " | " << (r.steady ? "yes" : "no") << " | " << fmt(r.value, 4) << " ± " << fmt(r.value_ci, 2) << " | "
         << fmt(r.error) << " | "
         << (angle ? fmt(r.wall_pressure_ratio, 4) : "") << " | "
         << (r.family == "clustered" ? fmt(r.speedup_cfd, 3) : "") << " |\n";
  md << "\n## Figures\n\n";
  auto img = [&](const std::string& file, const std::string& caption) {
    if (fs::exists(fig + "/" + file)) md << "![" << caption << "](figures/" << file << ")\n\n*" << caption << "*\n\n";
  };
  img("error_vs_time.png", "Error against CFD wall time");
  img("error_vs_cells.png", "Error against cells");
  img("granular_volume_fraction.png", "Granular volume fraction with the fitted shock");
  img("granular_velocity.png", "Granular velocity u");
  img("shocks_compared.png", "Granular, CFD and exact shocks");
  for (const auto* fam : {&c.uniform, &c.clustered})
    for (const auto& r : *fam) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s_h%g", r.family.c_str(), r.level);
      img("mesh_" + std::string(buf) + "_mesh.png", std::string("Grid ") + buf);
      img("cfd_" + std::string(buf) + "_history.png", std::string("Convergence history ") + buf);
      img("cfd_" + std::string(buf) + "_convergence.png", std::string("Convergence history ") + buf);
      img("cfd_mach_" + std::string(buf) + ".png", std::string("CFD Mach number ") + buf);
    }
  md << "Errors are against the reference; ± is the 95% interval of the shock located on the CFD solution "
        "(its noise floor limits how small an error can be resolved).\n\n";
  md << "Total pipeline wall time: " << fmt(in.total_seconds, 4) << " s (cached stages cost nothing).\n";
  scene::write_file_atomic(dir + "/report.md", md.str());
}

}  // namespace pipeline
