#pragma once
// Grid pictures with gnuplot (pngcairo): the whole grid and a zoom on the
// shock. Best effort: the caller never fails a run because of a plot.
#include <string>
#include <vector>

#include "gmsh_mesher.hpp"
#include "meshgen/fluid_region.hpp"
#include "meshgen/size_field.hpp"

namespace meshgen {

struct PlotWindow {
  scene::Vec2 center;
  double half = 0.1;
};

// Writes DIR/mesh.png and DIR/mesh_zoom.png; returns the names written.
// Throws (any exception) when gnuplot is missing or fails.
std::vector<std::string> plot_mesh(const PlaneMesh& mesh, const std::vector<ShockRun>& shock,
                                   const FluidRegion& region, const PlotWindow& zoom, const std::string& title,
                                   const std::string& dir);

}  // namespace meshgen
