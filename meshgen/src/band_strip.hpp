#pragma once
// Shock-aligned cells in the shock band (mesh.anisotropy > 1): a structured
// strip of quads laid along the clipped shock curve, thin across the shock
// and long along it. Pure geometry (no gmsh): gmsh_mesher.cpp turns each
// strip into a transfinite surface and meshes the rest of the region round
// it with BandSize as the size callback.
//
// gmsh 4.8's anisotropic route (BAMG with a tensor background view) was
// tried first: Debian's build returns isotropic triangles of the metric's
// mean size whatever the tensor, so the band is built explicitly instead.
//
// Along-shock cell length at a station (the rule, docs/meshgen.md):
//   l = min(a h_min, kCurvatureCells R)
// a = mesh.anisotropy, R the shock's radius of curvature measured over a
// window of a h_min either side; l grows by at most kAlongGrowth from one
// cell to the next. Rows across the shock: the band (the run's largest
// half-width w, the prediction's ci included) in equal rows of at most
// h_min, the same at every station, then kGrowthRows-ratio rows out to a row
// of l / kEdgeJump, where the isotropic grid (size l there) takes over.
#include <cstddef>
#include <vector>

#include "meshgen/fluid_region.hpp"
#include "meshgen/size_field.hpp"
#include "scene/vec2.hpp"

namespace meshgen {

struct StripRule {
  double h_min = 0.01;      // row thickness in the band (scene coordinates)
  double max_aspect = 1.0;  // mesh.anisotropy
  double h_max = 0.05;
  double growth = 1.2;  // the isotropic grid's size growth round the strip
};

// One structured strip: stations along the shock, each a straight column of
// nodes along the local normal. Node (i, j) = centre[i] + rows[j] normal[i].
struct ShockStrip {
  std::vector<scene::Vec2> centre, normal;
  std::vector<double> rows;   // offsets along the normal, ascending, symmetric about 0
  std::vector<double> along;  // station spacing l (one per cell, stations - 1)

  std::size_t stations() const { return centre.size(); }
  scene::Vec2 node(std::size_t i, std::size_t j) const { return centre[i] + rows[j] * normal[i]; }
  // Closed outline (no repeat): the j = 0 side forward, the last column up,
  // the top side back, the first column down.
  std::vector<scene::Vec2> outline() const;
  std::size_t cells() const { return (stations() - 1) * (rows.size() - 1); }
};

struct BandLayout {
  std::vector<ShockStrip> strips;
  // The shock pieces no strip covers (near the body and the domain edges,
  // where a strip would not fit): they keep today's isotropic h_min band.
  std::vector<ShockRun> uncovered;
};

// Lays strips along the runs, trimmed to stay kStripMargin h_min inside the
// region and off each other; a run too short or too curved for a strip
// stays wholly uncovered.
BandLayout layout_strips(const std::vector<ShockRun>& runs, const FluidRegion& region,
                         const StripRule& rule);

// The size callback of the unstructured grid round the strips: today's field
// round the uncovered shock pieces and the body, and round each strip
//   h = l_edge + (growth - 1) d
// with l_edge the node spacing on the strip's outline (l on its sides, the
// row thickness on its end columns) and d the distance to the outline.
class BandSize {
 public:
  BandSize(const SizeParams& p, const BandLayout& layout,
           const std::vector<scene::Vec2>& body_polyline);
  double operator()(scene::Vec2 p) const;

 private:
  SizeField base_;
  SegmentIndex edges_;
  double slope_;
  double h_max_;
};

// Cells of a grid laid round strips, before gmsh runs: the strips' own
// cells exactly, and estimate_cells' sum(dA / h^2) of `size` over the region
// outside them (the caller's cells per h^2 turn it into cells).
struct StripGridCount {
  double strip_cells = 0.0;
  double unstructured = 0.0;  // sum(dA / h^2) outside the strips
};
StripGridCount count_cells(const BandLayout& layout, const BandSize& size,
                           const FluidRegion& region);

// Band cell shape in the local shock frame (the nearest shock segment):
// aspect = the larger over the smaller of the cell's extents along the
// shock and across it; thickness = its extent across the shock.
struct BandShape {
  double max_aspect = 0.0, mean_aspect = 0.0;
  double max_thickness = 0.0;  // extent along the nearest shock segment's normal
  long cells = 0;
};
// Adds one band cell (its corner points) to the statistics; `runs` give the
// local shock direction.
class BandShapeMeter {
 public:
  explicit BandShapeMeter(const std::vector<ShockRun>& runs);
  void add(const std::vector<scene::Vec2>& corners);
  BandShape result() const;

 private:
  scene::Vec2 normal_near(scene::Vec2 p) const;
  std::vector<std::pair<scene::Vec2, scene::Vec2>> segs_;
  BandShape s_;
  double sum_ = 0.0;
};

}  // namespace meshgen
