#include "plot.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/gnuplot.hpp"

namespace meshgen {

using scene::Vec2;

namespace {

constexpr double kBoundarySag = 1e-3;  // body lengths, for drawing arcs

void write_cells(std::ostream& os, const PlaneMesh& m, const PlotWindow* window) {
  for (const auto& c : m.cells) {
    const int n = c[3] < 0 ? 3 : 4;
    if (window) {
      bool near = false;
      for (int k = 0; k < n; ++k) {
        const Vec2 p = m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])];
        near = near || (std::abs(p.x - window->center.x) <= 1.2 * window->half &&
                        std::abs(p.y - window->center.y) <= 1.2 * window->half);
      }
      if (!near) continue;
    }
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k % n)])];
      os << p.x << ' ' << p.y << '\n';
    }
    os << '\n';
  }
}

}  // namespace

std::vector<std::string> plot_mesh(const PlaneMesh& mesh, const std::vector<ShockRun>& shock,
                                   const FluidRegion& region, const PlotWindow& zoom, const std::string& title,
                                   const std::string& dir) {
  const std::string data = dir + "/plot_data";
  std::filesystem::create_directories(data);
  {
    std::ofstream all(data + "/cells.dat"), near(data + "/zoom.dat");
    write_cells(all, mesh, nullptr);
    write_cells(near, mesh, &zoom);
    std::ofstream sh(data + "/shock.dat"), bd(data + "/boundary.dat");
    for (const ShockRun& r : shock) {
      for (const Vec2 p : r.points) sh << p.x << ' ' << p.y << '\n';
      sh << '\n';
    }
    sh << "nan nan\n";  // gnuplot wants at least one record
    for (const auto& loop : region.loops)
      for (const BoundaryCurve& c : loop) {
        for (const Vec2 p : sample_curve(c, kBoundarySag * region.length_scale)) bd << p.x << ' ' << p.y << '\n';
        bd << '\n';
      }
  }
  const scene::Domain& d = region.domain;
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1600,1000 noenhanced font ',12'\n"
     << "set size ratio -1\nset key top left\n"
     << "set output 'mesh.png'\nset title "
     << scene::gnuplot_string(title + " (" + std::to_string(mesh.cells.size()) + " cells)") << "\n"
     << "set xrange [" << d.xmin << ":" << d.xmax << "]\nset yrange [" << d.ymin << ":" << d.ymax << "]\n"
     << "plot 'plot_data/cells.dat' w l lc rgb '#404040' lw 0.4 notitle, "
     << "'plot_data/boundary.dat' w l lc rgb 'blue' lw 1.5 title 'boundary', "
     << "'plot_data/shock.dat' w l lc rgb 'red' lw 1.5 title 'predicted shock'\n"
     << "set output 'mesh_zoom.png'\nset title " << scene::gnuplot_string(title + ": zoom at the shock") << "\n"
     << "set xrange [" << zoom.center.x - zoom.half << ":" << zoom.center.x + zoom.half << "]\n"
     << "set yrange [" << zoom.center.y - zoom.half << ":" << zoom.center.y + zoom.half << "]\n"
     << "plot 'plot_data/zoom.dat' w l lc rgb '#404040' lw 0.8 notitle, "
     << "'plot_data/boundary.dat' w l lc rgb 'blue' lw 2 title 'boundary', "
     << "'plot_data/shock.dat' w l lc rgb 'red' lw 2 title 'predicted shock'\n";
  {
    std::ofstream f(dir + "/plot.gp");
    f << gp.str();
  }
  // gnuplot runs in `dir`: the script names its files relative to it.
  try {
    scene::run_gnuplot(dir + "/plot.gp", dir, dir + "/log.gnuplot");
  } catch (const scene::RunError&) {
    std::filesystem::remove_all(data);
    std::filesystem::remove(dir + "/plot.gp");
    throw;
  }
  std::filesystem::remove_all(data);
  std::filesystem::remove(dir + "/plot.gp");
  std::filesystem::remove(dir + "/log.gnuplot");
  return {"mesh.png", "mesh_zoom.png"};
}

}  // namespace meshgen
