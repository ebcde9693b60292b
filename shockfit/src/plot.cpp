#include "plot.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/gnuplot.hpp"
#include "shockfit/profile.hpp"
#include "shockfit/two_line_fit.hpp"

namespace shockfit {

namespace fs = std::filesystem;

namespace {
// The joint shock is located on two fields; the pictures draw the
// density-like one.
std::string drawn_field(const std::string& located_on) {
  return split_field_label(located_on).first;
}

constexpr int kPixelsWide = 1100;
constexpr int kProfileWide = 900, kProfileHigh = 600;
// Each PNG is at most this tall (very slender domains).
constexpr int kMaxPixelsHigh = 1600;

std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  if (std::isfinite(v)) os << v; else os << "NaN";
  return os.str();
}

}  // namespace

bool write_plots(const scene::Scene& s, const scene::Lattice& lat, const ShockResult& r,
                 const std::string& out_dir, std::string& why) {
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  const fs::path dir(out_dir);
  // gnuplot runs in out_dir, so the script names its files by these names
  // alone (our own characters), never by a path that holds the user's.
  const std::string tag = ".shockfit_plot_" + std::to_string(::getpid());
  const auto name = [](const fs::path& p) { return scene::gnuplot_path(p.filename().string()); };
  const fs::path f_field = dir / (tag + "_field.dat"), f_body = dir / (tag + "_body.dat"),
                 f_st = dir / (tag + "_stations.dat"), f_fit = dir / (tag + "_fit.dat"),
                 f_prof = dir / (tag + "_profile.dat"), f_lines = dir / (tag + "_lines.dat"),
                 f_gp = dir / (tag + ".gp"), f_log = dir / (tag + ".log");
  const fs::path png1 = dir / "shock.png", png2 = dir / "profile.png";
  const fs::path tmp1 = dir / (tag + "_shock.png"), tmp2 = dir / (tag + "_profile.png");
  {
    std::ofstream o(f_field);
    const auto& f = lat.field(drawn_field(r.field));
    for (int j = 0; j < lat.ny; ++j) {
      for (int i = 0; i < lat.nx; ++i) o << num(lat.xc(i)) << ' ' << num(lat.yc(j)) << ' ' << num(f[lat.index(i, j)]) << '\n';
      o << '\n';
    }
  }
  {
    std::ofstream o(f_body);
    for (const auto p : g.polyline) o << num(p.x) << ' ' << num(p.y) << '\n';
    o << num(g.polyline.front().x) << ' ' << num(g.polyline.front().y) << '\n';
  }
  {
    std::ofstream o(f_st);
    for (const StationFit& f : r.stations)
      o << num(f.surface.x) << ' ' << num(f.surface.y) << ' ' << num(f.shock.x) << ' ' << num(f.shock.y) << ' '
        << (f.accepted ? 1 : 0) << '\n';
  }
  {
    std::ofstream o(f_fit);
    if (r.shock == scene::ShockKind::attached) {
      const double span = std::hypot(d.width(), d.height());
      for (const double u : {-span, span}) {
        const scene::Vec2 q = r.line_point + u * r.line_dir;
        o << num(q.x) << ' ' << num(q.y) << '\n';
      }
    } else if (r.shock == scene::ShockKind::detached && std::isfinite(r.vertex_x) &&
               std::isfinite(r.curvature_radius)) {
      const double rc = r.curvature_radius * g.length;
      constexpr int kCurvePoints = 101;
      const double ymax = std::min(d.height(), 2.0 * rc);
      for (int k = 0; k < kCurvePoints; ++k) {
        const double y = (d.symmetric ? 0.0 : -ymax) + (d.symmetric ? 1.0 : 2.0) * ymax * k / (kCurvePoints - 1);
        o << num(r.vertex_x + y * y / (2.0 * rc)) << ' ' << num(y + g.nose.y) << '\n';
      }
    }
  }
  // One station's profile with its two lines.
  const bool have_profile = r.plot_station >= 0 && r.plot_station < static_cast<int>(r.stations.size());
  double shock_t = 0.0;
  if (have_profile) {
    const StationFit& sf = r.stations[static_cast<std::size_t>(r.plot_station)];
    const Profile prof = sample_profile(lat, drawn_field(r.field), d, sf.surface, sf.normal, s.shockfit.min_samples);
    const TwoLineOptions opt = two_line_options(prof, s.shockfit);
    const TwoLineFit fit = fit_two_lines(prof.t, prof.f, opt);
    std::ofstream o(f_prof);
    for (std::size_t k = 0; k < prof.t.size(); ++k) o << num(prof.t[k]) << ' ' << num(prof.f[k]) << '\n';
    std::ofstream l(f_lines);
    if (fit.valid) {
      const double ta = prof.t.front(), tb = prof.t.back();
      l << num(ta) << ' ' << num(fit.inner.at(ta)) << '\n' << num(fit.t_break + opt.window) << ' '
        << num(fit.inner.at(fit.t_break + opt.window)) << "\n\n\n";
      l << num(fit.t_break - opt.window) << ' ' << num(fit.outer.at(fit.t_break - opt.window)) << '\n' << num(tb) << ' '
        << num(fit.outer.at(tb)) << '\n';
      shock_t = fit.position;
    }
  }
  const double aspect = std::clamp(d.height() / std::max(d.width(), 1e-300), 0.1, 3.0);
  const int high = std::min(kMaxPixelsHigh, static_cast<int>(kPixelsWide * aspect) + 80);
  {
    std::ofstream o(f_gp);
    o << "set terminal pngcairo size " << kPixelsWide << "," << high << " font 'sans,10'\n"
      << "set output " << name(tmp1) << "\n"
      << "set title "
      << scene::gnuplot_string(s.name + ": field " + r.field + ", shock " + scene::to_string(r.shock))
      << " noenhanced\n"
      << "set size ratio -1\nset xrange [" << num(d.xmin) << ":" << num(d.xmax) << "]\nset yrange [" << num(d.ymin)
      << ":" << num(d.ymax) << "]\n"
      << "set xlabel 'x / L'\nset ylabel 'y / L'\nset palette rgb 33,13,10\n"
      << "set key bottom right opaque\nset clip two\n"
      << "plot " << name(f_field) << " using 1:2:3 with image notitle, \\\n"
      << "  " << name(f_body) << " using 1:2 with lines lw 2 lc rgb 'black' title 'body', \\\n"
      << "  " << name(f_st) << " using 1:2:($5>0?$3-$1:NaN):($5>0?$4-$2:NaN) with vectors nohead lc rgb 'white' lw 0.5 notitle, \\\n"
      << "  " << name(f_st) << " using 1:2 with points pt 7 ps 0.5 lc rgb 'black' title 'stations', \\\n"
      << "  " << name(f_st) << " using ($5>0?$3:NaN):4 with points pt 6 ps 1 lc rgb 'red' title 'shock points', \\\n"
      << "  " << name(f_st) << " using ($5>0?NaN:$3):4 with points pt 2 ps 0.8 lc rgb 'gray' title 'rejected', \\\n"
      << "  " << name(f_fit) << " using 1:2 with lines lw 2 dt 2 lc rgb 'red' title 'fitted shock'\n";
    if (have_profile) {
      o << "set output " << name(tmp2) << "\nset size noratio\nset size 1,1\nset autoscale\nset terminal pngcairo size " << kProfileWide
        << "," << kProfileHigh << " font 'sans,10'\n"
        << "set title " << scene::gnuplot_string("station " + std::to_string(r.plot_station) + ": " + r.field +
                                                 " along the normal")
        << " noenhanced\n"
        << "set xlabel 'distance from the surface / L'\nset ylabel " << scene::gnuplot_string(r.field)
        << " noenhanced\n"
        << "set key top right\nset arrow from " << num(shock_t) << ", graph 0 to " << num(shock_t)
        << ", graph 1 nohead dt 3 lc rgb 'red'\n"
        << "plot " << name(f_prof) << " using 1:2 with points pt 7 ps 0.5 lc rgb 'black' title 'samples', \\\n"
        << "  " << name(f_lines) << " index 0 using 1:2 with lines lw 2 lc rgb 'blue' title 'inner line', \\\n"
        << "  " << name(f_lines) << " index 1 using 1:2 with lines lw 2 lc rgb 'dark-green' title 'outer line'\n";
    }
    o << "unset output\n";
  }
  bool ok = true;
  try {
    scene::run_gnuplot(f_gp.string(), dir.string(), f_log.string());
  } catch (const scene::RunError& e) {
    why = e.what();
    ok = false;
  }
  std::error_code ec;
  if (ok) {
    fs::rename(tmp1, png1, ec);
    if (!ec && have_profile) fs::rename(tmp2, png2, ec);
    if (ec) why = "could not move the PNG into place: " + ec.message();
  }
  for (const auto& p : {f_field, f_body, f_st, f_fit, f_prof, f_lines, f_gp, f_log, tmp1, tmp2}) fs::remove(p, ec);
  return ok && why.empty();
}

}  // namespace shockfit
