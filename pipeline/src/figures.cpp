#include "pipeline/figures.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pipeline/plot.hpp"
#include "scene/gnuplot.hpp"

namespace pipeline {

namespace fs = std::filesystem;

bool field_png(const scene::Lattice& lat, const std::string& field, const std::string& title,
               const std::vector<Overlay>& overlays, const std::string& png_path) {
  if (!lat.has(field)) return false;
  const fs::path png(png_path);
  const std::string dir = png.parent_path().string();
  fs::create_directories(dir);
  const std::string data = dir + "/." + png.stem().string() + ".dat";
  {
    std::ofstream os(data);
    const auto& f = lat.field(field);
    for (int j = 0; j < lat.ny; ++j) {
      for (int i = 0; i < lat.nx; ++i) {
        const double v = f[lat.index(i, j)];
        os << lat.xc(i) << " " << lat.yc(j) << " ";
        if (std::isfinite(v)) os << v; else os << "NaN";
        os << "\n";
      }
      os << "\n";
    }
  }
  const double aspect = (lat.ny * lat.dy) / (lat.nx * lat.dx);
  const int w = 1000, h = std::clamp(static_cast<int>(w * aspect) + 120, 300, 1400);
  std::ostringstream gp;
  // run_gnuplot runs in `dir`: files are named relative to it.
  gp << "set terminal pngcairo size " << w << "," << h << " font 'DejaVu Sans,11'\n"
     << "set output " << scene::gnuplot_path(png.filename().string() + ".tmp") << "\n"
     << "set title " << scene::gnuplot_string(title) << "\nset size ratio -1\nset xlabel 'x / L'\nset ylabel 'y / L'\n"
     << "set xrange [" << lat.x0 << ":" << lat.x0 + lat.nx * lat.dx << "]\nset yrange [" << lat.y0 << ":"
     << lat.y0 + lat.ny * lat.dy << "]\nset palette rgb 33,13,10\nset key outside bottom center horizontal\n"
     << "set termoption noenhanced\n";
  std::ostringstream inl;
  gp << "plot " << scene::gnuplot_path(fs::path(data).filename().string()) << " using 1:2:3 with image title "
     << scene::gnuplot_string(field);
  for (std::size_t k = 0; k < overlays.size(); ++k) {
    if (overlays[k].points.empty()) continue;
    gp << ", $o" << k << " with " << overlays[k].style << " title " << scene::gnuplot_string(overlays[k].title);
    inl << "$o" << k << " << EOD\n";
    for (const auto& p : overlays[k].points) inl << p.x << " " << p.y << "\n";
    inl << "EOD\n";
  }
  gp << "\nset output\n";
  const bool ok = run_gnuplot(inl.str() + gp.str(), dir);
  std::error_code ec;
  fs::remove(data, ec);
  if (!ok) return false;
  fs::rename(dir + "/" + png.filename().string() + ".tmp", png_path, ec);
  return !ec;
}

}  // namespace pipeline
