#pragma once
// The flow region cut by vertical lines into pieces of about equal
// estimated cell counts (private), so gmsh can mesh them on several
// threads: each piece as closed loops of the region's curves (those a cut
// crosses split there) and the cuts bounding it.
#include <functional>
#include <optional>
#include <vector>

#include "meshgen/fluid_region.hpp"

namespace meshgen {

struct PieceCurve {
  BoundaryCurve curve;
  int cut = -1;  // the cut (index into RegionPieces::x) it runs along; -1: a boundary curve (curve.patch)
};

struct RegionPieces {
  std::vector<double> x;  // the cuts, left to right
  // Left to right, each piece its outer loop (counter-clockwise), then its holes.
  std::vector<std::vector<std::vector<PieceCurve>>> loops;
};

// Up to `pieces` pieces: cuts x = const at equal fractions of the
// estimated cell count (the integral of 1/size^2), or near them; a cut must
// cross the outer loop on exactly two straight curves, away from their
// ends, and pass no hole, else it is left out. nullopt when no cut is found
// (the region is then meshed whole).
std::optional<RegionPieces> split_region(const FluidRegion& region, const std::function<double(scene::Vec2)>& size,
                                         int pieces);

}  // namespace meshgen
