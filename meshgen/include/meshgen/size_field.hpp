#pragma once
// Target cell size h(x, y) of the clustered grid, and the shock curve it is
// built round (clipped to the flow region). Pure geometry: no gmsh here, so
// it can be tested and integrated (cell-count estimates) on its own.
//
//   h = min(h_shock, h_wall, h_max)
//   h_shock = h_min                             within the band, d <= w
//           = h_min + (growth - 1) (d - w)      outside it
//   h_wall  = h_body + (growth - 1) d_body      (h_body: h_min by default)
// A size that grows by (growth - 1) per unit distance makes each cell
// `growth` times its neighbour: h(d + h) = h (1 + growth - 1).
//
// An adapted field takes h from a lattice instead of the shock band:
//   h = min(clamp(scale * h_lattice, h_min, h_max), h_wall)
// with h_lattice interpolated bilinearly between cell centres (and held at
// the outermost centres beyond them): the same body rule as the clustered
// grids, whatever made the lattice.
#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "meshgen/fluid_region.hpp"
#include "scene/lattice.hpp"
#include "scene/vec2.hpp"

namespace meshgen {

// Polyline runs of the shock curve inside the flow region, with the band
// half-width at each vertex.
struct ShockRun {
  std::vector<scene::Vec2> points;
  std::vector<double> half_width;
};

// Clips the curve (points in order, half-width per point) to the region:
// parts outside the rectangle or inside the body are dropped, segments cut
// where they cross (to `resolution`). Empty when nothing is inside.
std::vector<ShockRun> clip_shock(const std::vector<scene::Vec2>& curve, const std::vector<double>& half_width,
                                 const FluidRegion& region, double resolution);

struct SizeParams {
  double h_min = 0.01, h_max = 0.05, h_body = 0.02, growth = 1.2;
};

// Cell size on the body surface, scene units. The wall is where the flow is
// turned: the slip condition sets the flow direction that fixes an attached
// shock's angle from the apex on and a bow shock's stand-off from the
// stagnation region, so by default it is resolved like the shock, at h_min
// (as the uniform grid of that h_min resolves it), and grows from there at
// the grid's growth rate. An explicit h_body overrides it, within
// [h_min, h_max].
inline double body_cell_size(std::optional<double> h_body, double h_min, double h_max) {
  return h_body ? std::clamp(*h_body, h_min, h_max) : h_min;
}

// Half-width of the shock band where the prediction states no interval
// (band_width if given, else kDefaultBandCells h_min), never under
// kMinBandCells h_min: even a sure prediction gets a few fine cells across.
// A stated 95% half-width widens it further point by point (meshgen's plan).
inline double band_half_width(std::optional<double> band_width, double h_min) {
  constexpr double kDefaultBandCells = 3.0;
  constexpr double kMinBandCells = 2.0;
  return std::max(band_width.value_or(kDefaultBandCells * h_min), kMinBandCells * h_min);
}

// Segments in a bucket grid, for nearest-distance queries up to a cut-off.
class SegmentIndex {
 public:
  SegmentIndex() = default;
  // values: one per point (a band half-width, or empty for zeros).
  void add_polyline(const std::vector<scene::Vec2>& pts, const std::vector<double>& values);
  // After the last add: excesses beyond `cutoff` need not be exact.
  void build(double cutoff);
  // min over segments of (distance - value interpolated at the nearest
  // point): how far p lies outside the band; +inf beyond the cut-off.
  double excess(scene::Vec2 p) const;

 private:
  struct Seg {
    scene::Vec2 a, b;
    double va, vb;
  };
  std::vector<Seg> segs_;
  std::vector<std::vector<int>> cells_;
  double x0_ = 0, y0_ = 0, cell_ = 1, cutoff_ = 1;
  int nx_ = 0, ny_ = 0;
};

class SizeField {
 public:
  // Uniform field.
  explicit SizeField(double h);
  // Clustered field round the clipped shock runs and the body outline.
  SizeField(const SizeParams& p, const std::vector<ShockRun>& shock, const std::vector<scene::Vec2>& body_polyline);
  // Adapted field: the lattice's finite, positive field "h" times `scale`
  // (lattice units to scene coordinates), clamped and limited by the body rule.
  SizeField(const SizeParams& p, std::shared_ptr<const scene::Lattice> h_lattice, double scale,
            const std::vector<scene::Vec2>& body_polyline);
  double operator()(scene::Vec2 p) const;
  // Whether p lies in the fine band (d <= w of the nearest shock point).
  bool in_band(scene::Vec2 p) const;
  bool uniform() const { return uniform_; }
  const SizeParams& params() const { return p_; }

 private:
  double lattice_h(scene::Vec2 p) const;

  bool uniform_ = true;
  SizeParams p_;
  SegmentIndex shock_, body_;
  std::shared_ptr<const scene::Lattice> lattice_;  // adapted fields only
  const std::vector<double>* lattice_values_ = nullptr;  // its field "h"
  double lattice_scale_ = 1.0;
};

// Estimated number of cells sum(dA / h^2) over the region, on a fine lattice.
double estimate_cells(const SizeField& f, const FluidRegion& region);
// The same sum for any size function, leaving out the points inside
// `holes` (closed simple polygons: parts of the grid counted otherwise, such
// as structured strips).
double estimate_cells(const std::function<double(scene::Vec2)>& h, const FluidRegion& region,
                      const std::vector<std::vector<scene::Vec2>>& holes);

}  // namespace meshgen
