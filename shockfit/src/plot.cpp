#include "plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "scene/body.hpp"
#include "shockfit/profile.hpp"
#include "shockfit/two_line_fit.hpp"

extern char** environ;

namespace shockfit {

namespace fs = std::filesystem;

namespace {

constexpr int kPixelsWide = 1100;
constexpr int kProfileWide = 900, kProfileHigh = 600;
// Each PNG is at most this tall (very slender domains).
constexpr int kMaxPixelsHigh = 1600;

std::string find_in_path(const std::string& exe) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path p = fs::path(dir) / exe;
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return "";
}

// Runs gnuplot on `script` with its output to `log`; true on exit status 0.
bool run_gnuplot(const std::string& gnuplot, const std::string& script, const std::string& log, std::string& why) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> args{gnuplot, script};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, gnuplot.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    why = "could not start gnuplot";
    return false;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    why = "gnuplot failed: " + last;
    return false;
  }
  return true;
}

std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  if (std::isfinite(v)) os << v; else os << "NaN";
  return os.str();
}

}  // namespace

bool write_plots(const scene::Scene& s, const scene::Lattice& lat, const ShockResult& r,
                 const std::string& out_dir, std::string& why) {
  const std::string gnuplot = find_in_path("gnuplot");
  if (gnuplot.empty()) {
    why = "gnuplot not found on PATH";
    return false;
  }
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  const fs::path dir(out_dir);
  const std::string tag = ".shockfit_plot_" + std::to_string(::getpid());
  const fs::path f_field = dir / (tag + "_field.dat"), f_body = dir / (tag + "_body.dat"),
                 f_st = dir / (tag + "_stations.dat"), f_fit = dir / (tag + "_fit.dat"),
                 f_prof = dir / (tag + "_profile.dat"), f_lines = dir / (tag + "_lines.dat"),
                 f_gp = dir / (tag + ".gp"), f_log = dir / (tag + ".log");
  const fs::path png1 = dir / "shock.png", png2 = dir / "profile.png";
  const fs::path tmp1 = dir / (tag + "_shock.png"), tmp2 = dir / (tag + "_profile.png");
  {
    std::ofstream o(f_field);
    const auto& f = lat.field(r.field);
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
    if (r.shock == "attached") {
      const double span = std::hypot(d.width(), d.height());
      for (const double u : {-span, span}) {
        const scene::Vec2 q = r.line_point + u * r.line_dir;
        o << num(q.x) << ' ' << num(q.y) << '\n';
      }
    } else if (r.shock == "detached" && std::isfinite(r.vertex_x) && std::isfinite(r.curvature_radius)) {
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
    const Profile prof = sample_profile(lat, r.field, d, sf.surface, sf.normal, s.shockfit.min_samples);
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
      << "set output '" << tmp1.string() << "'\n"
      << "set title \"" << s.name << ": field " << r.field << ", shock " << r.shock << "\" noenhanced\n"
      << "set size ratio -1\nset xrange [" << num(d.xmin) << ":" << num(d.xmax) << "]\nset yrange [" << num(d.ymin)
      << ":" << num(d.ymax) << "]\n"
      << "set xlabel 'x / L'\nset ylabel 'y / L'\nset palette rgb 33,13,10\n"
      << "set key bottom right opaque\nset clip two\n"
      << "plot '" << f_field.string() << "' using 1:2:3 with image notitle, \\\n"
      << "  '" << f_body.string() << "' using 1:2 with lines lw 2 lc rgb 'black' title 'body', \\\n"
      << "  '" << f_st.string() << "' using 1:2:($5>0?$3-$1:NaN):($5>0?$4-$2:NaN) with vectors nohead lc rgb 'white' lw 0.5 notitle, \\\n"
      << "  '" << f_st.string() << "' using 1:2 with points pt 7 ps 0.5 lc rgb 'black' title 'stations', \\\n"
      << "  '" << f_st.string() << "' using ($5>0?$3:NaN):4 with points pt 6 ps 1 lc rgb 'red' title 'shock points', \\\n"
      << "  '" << f_st.string() << "' using ($5>0?NaN:$3):4 with points pt 2 ps 0.8 lc rgb 'gray' title 'rejected', \\\n"
      << "  '" << f_fit.string() << "' using 1:2 with lines lw 2 dt 2 lc rgb 'red' title 'fitted shock'\n";
    if (have_profile) {
      o << "set output '" << tmp2.string() << "'\nset size noratio\nset size 1,1\nset autoscale\nset terminal pngcairo size " << kProfileWide
        << "," << kProfileHigh << " font 'sans,10'\n"
        << "set title \"station " << r.plot_station << ": " << r.field << " along the normal\" noenhanced\n"
        << "set xlabel 'distance from the surface / L'\nset ylabel '" << r.field << "' noenhanced\n"
        << "set key top right\nset arrow from " << num(shock_t) << ", graph 0 to " << num(shock_t)
        << ", graph 1 nohead dt 3 lc rgb 'red'\n"
        << "plot '" << f_prof.string() << "' using 1:2 with points pt 7 ps 0.5 lc rgb 'black' title 'samples', \\\n"
        << "  '" << f_lines.string() << "' index 0 using 1:2 with lines lw 2 lc rgb 'blue' title 'inner line', \\\n"
        << "  '" << f_lines.string() << "' index 1 using 1:2 with lines lw 2 lc rgb 'dark-green' title 'outer line'\n";
    }
    o << "unset output\n";
  }
  const bool ok = run_gnuplot(gnuplot, f_gp.string(), f_log.string(), why);
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
