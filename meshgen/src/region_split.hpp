#pragma once
// The flow region cut in two by a vertical line (private), so gmsh can mesh
// the halves on two threads: both pieces as closed loops of the region's
// curves (the two it crosses split at the cut) plus the cut itself.
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "meshgen/fluid_region.hpp"

namespace meshgen {

struct PieceCurve {
  BoundaryCurve curve;
  bool cut = false;  // the cut between the pieces (no patch); else curve.patch
};

struct RegionPieces {
  double x = 0.0;  // where the cut runs
  // [0] left, [1] right: each its outer loop (counter-clockwise), then its holes.
  std::array<std::vector<std::vector<PieceCurve>>, 2> loops;
};

// The cut x = const that halves the estimated cell count (the integral of
// 1/size^2), or one near it: the cut must cross the outer loop on exactly
// two straight curves, away from their ends, and pass no hole. nullopt when
// no such line is found (the region is then meshed whole).
std::optional<RegionPieces> split_region(const FluidRegion& region,
                                         const std::function<double(scene::Vec2)>& size);

}  // namespace meshgen
