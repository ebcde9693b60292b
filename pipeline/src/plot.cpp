#include "pipeline/plot.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/gnuplot.hpp"
#include "scene/progress.hpp"

namespace pipeline {

namespace fs = std::filesystem;

bool run_gnuplot(const std::string& script, const std::string& work_dir) {
  const std::string path = work_dir + "/.plot.gp";
  {
    std::ofstream os(path);
    os << script;
  }
  // gnuplot runs in work_dir: scripts name their files relative to it.
  try {
    scene::run_gnuplot(path, work_dir, work_dir + "/.plot.log");
  } catch (const scene::RunError& e) {
    scene::log_line(std::string("pipeline: warning: ") + e.what() + "; figure skipped", true);
    return false;
  }
  std::error_code ec;
  fs::remove(path, ec);
  return true;
}

bool plot_png(const PlotSpec& spec, const std::string& png_path) {
  const fs::path png(png_path);
  const std::string dir = png.has_parent_path() ? png.parent_path().string() : ".";
  fs::create_directories(dir);
  std::ostringstream gp;
  gp << "set terminal pngcairo size " << spec.width << "," << spec.height << " font 'DejaVu Sans,11'\n"
     << "set output " << scene::gnuplot_path(png.filename().string() + ".tmp") << "\n"
     << "set title " << scene::gnuplot_string(spec.title) << "\nset xlabel " << scene::gnuplot_string(spec.xlabel)
     << "\nset ylabel " << scene::gnuplot_string(spec.ylabel)
     << "\nset grid\nset key top right\nset termoption noenhanced\n";
  if (spec.logx) gp << "set logscale x\n";
  if (spec.logy) gp << "set logscale y\n";
  for (const auto& e : spec.extra) gp << e << "\n";
  std::ostringstream data;
  gp << "plot ";
  bool first = true;
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const auto& s = spec.series[k];
    if (s.x.empty()) continue;
    const bool bars = s.yerr.size() == s.y.size();
    gp << (first ? "" : ", ") << "$d" << k;
    if (bars) gp << " using 1:2:3 with yerrorlines"; else gp << " with " << s.style;
    gp << " title " << scene::gnuplot_string(s.title);
    first = false;
    data << "$d" << k << " << EOD\n";
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      data << s.x[i] << " " << s.y[i];
      if (bars) data << " " << s.yerr[i];
      data << "\n";
    }
    data << "EOD\n";
  }
  if (first) return false;  // nothing to plot
  gp << "\nset output\n";
  const std::string script = data.str() + gp.str();
  // gnuplot writes relative to its working directory, which is `dir`.
  if (!run_gnuplot(script, dir)) return false;
  std::error_code ec;
  fs::rename(dir + "/" + png.filename().string() + ".tmp", png_path, ec);
  return !ec;
}

}  // namespace pipeline
