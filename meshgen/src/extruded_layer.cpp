#include "extruded_layer.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "scene/errors.hpp"

namespace meshgen {

namespace {

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)),
             hi = static_cast<std::uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

double twice_signed_area(const PlaneMesh& m, const std::array<int, 4>& c) {
  const int n = corner_count(c);
  double s = 0.0;
  for (int k = 0; k < n; ++k) {
    const scene::Vec2 p = m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])];
    const scene::Vec2 q =
        m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>((k + 1) % n)])];
    s += p.x * q.y - q.x * p.y;
  }
  return s;
}

struct HalfEdge {
  std::uint64_t key = 0;
  int cell = 0, a = 0, b = 0;
};

std::string edge_name(const PlaneMesh& m, int a, int b) {
  const scene::Vec2 p = m.nodes[static_cast<std::size_t>(a)],
                    q = m.nodes[static_cast<std::size_t>(b)];
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")-(" + std::to_string(q.x) +
         ", " + std::to_string(q.y) + ")";
}

}  // namespace

ExtrudedLayer extrude_layer(const PlaneMesh& m) {
  ExtrudedLayer layer;
  layer.cells = m.cells;
  std::vector<HalfEdge> half;
  half.reserve(4 * m.cells.size());
  for (std::size_t i = 0; i < layer.cells.size(); ++i) {
    auto& c = layer.cells[i];
    const int n = corner_count(c);
    const double area2 = twice_signed_area(m, c);
    if (!(area2 != 0.0))
      throw scene::RunError("gmsh produced a cell of zero area (cell " + std::to_string(i) + ")");
    if (area2 < 0.0) std::reverse(c.begin(), c.begin() + n);
    for (int k = 0; k < n; ++k) {
      const int a = c[static_cast<std::size_t>(k)], b = c[static_cast<std::size_t>((k + 1) % n)];
      half.push_back({edge_key(a, b), static_cast<int>(i), a, b});
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key != y.key ? x.key < y.key : x.cell < y.cell;
  });

  std::unordered_map<std::uint64_t, Patch> patch_of;
  patch_of.reserve(m.boundary.size());
  for (const BoundaryEdge& e : m.boundary) patch_of.emplace(edge_key(e.a, e.b), e.patch);
  std::size_t boundary_faces = 0;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    const HalfEdge& h = half[i];
    if (j - i == 1) {
      const auto p = patch_of.find(h.key);
      if (p == patch_of.end())
        throw scene::RunError("meshgen: mesh edge " + edge_name(m, h.a, h.b) +
                              " has one cell but lies on no boundary curve (open mesh)");
      layer.boundary[static_cast<std::size_t>(p->second)].push_back({h.cell, -1, h.a, h.b});
      ++boundary_faces;
    } else if (j - i == 2 && half[i + 1].a == h.b && half[i + 1].b == h.a) {
      if (patch_of.count(h.key))
        throw scene::RunError("meshgen: boundary edge " + edge_name(m, h.a, h.b) +
                              " lies between two cells");
      layer.internal.push_back({h.cell, half[i + 1].cell, h.a, h.b});
    } else {
      throw scene::RunError("meshgen: mesh edge " + edge_name(m, h.a, h.b) + " is shared by " +
                            std::to_string(j - i) +
                            " cells or traversed twice the same way (overlapping cells)");
    }
    i = j;
  }
  if (boundary_faces != patch_of.size())
    throw scene::RunError("meshgen: " + std::to_string(m.boundary.size()) +
                          " boundary edges from gmsh, " + std::to_string(boundary_faces) +
                          " on the mesh's boundary");
  std::sort(layer.internal.begin(), layer.internal.end(),
            [](const LayerFace& x, const LayerFace& y) {
              return x.owner != y.owner ? x.owner < y.owner : x.neighbour < y.neighbour;
            });
  return layer;
}

}  // namespace meshgen
