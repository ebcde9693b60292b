#include "gmsh_mesher.hpp"

#include <gmsh.h>

#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "region_split.hpp"
#include "scene/errors.hpp"

namespace meshgen {

using scene::Vec2;

namespace {

// gmsh element types: 2-node line, 3-node triangle, 4-node quadrangle.
constexpr int kLine = 1, kTriangle = 2, kQuad = 3;
// Relative distance (body lengths) under which two boundary points are one.
constexpr double kSamePoint = 1e-10;
// Speed and cell quality decide (the budget is 10 s for 100k cells). CPU
// seconds, max non-orthogonality and skewness for 100k cells of wedge_M3_10
// (docs/meshgen.md):
//   Delaunay, simple recombination, 0 smoothing passes    4.2 s  55 deg  1.35
//   Delaunay, simple recombination, 1 pass (default)      6.3 s  32 deg  0.89
//   Frontal-Delaunay, simple recombination, 2 passes      7.7 s  33 deg  0.77
//   Frontal-Delaunay + Blossom (all quads)               > 90 s
// Frontal-Delaunay for Quads (algorithm 8) would pair up best but segfaults
// in Debian's gmsh 4.8.4 on every surface tried. Topology optimisation after
// recombination costs time and is left off.
constexpr int kAlgorithmDelaunay = 5, kAlgorithmFrontal = 6;  // mesh.algorithm
constexpr int kSimpleRecombination = 0;
constexpr int kRecombineOptimizeTopology = 0;

// gmsh keeps global state: initialise once per process, one mesh at a time.
std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

void ensure_initialized() {
  static std::once_flag once;
  std::call_once(once, [] {
    gmsh::initialize(0, nullptr, false);  // no user config files: deterministic
    gmsh::option::setNumber("General.Terminal", 0);
  });
}

void set_options(const GmshJob& job) {
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  // Threads mesh different surfaces at once (the pieces of a split region);
  // the size callback is const and safe to call from them.
  gmsh::option::setNumber("General.NumThreads", job.threads);
  gmsh::option::setNumber("Mesh.MaxNumThreads1D", 1);
  gmsh::option::setNumber("Mesh.MaxNumThreads2D", job.threads);
  gmsh::option::setNumber("Mesh.Algorithm", job.frontal ? kAlgorithmFrontal : kAlgorithmDelaunay);
  gmsh::option::setNumber("Mesh.RecombineAll", job.recombine ? 1 : 0);
  gmsh::option::setNumber("Mesh.RecombinationAlgorithm", kSimpleRecombination);
  gmsh::option::setNumber("Mesh.Smoothing", job.smoothing);
  gmsh::option::setNumber("Mesh.RecombineOptimizeTopology", kRecombineOptimizeTopology);
  // Sizes come from the callback alone.
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
  gmsh::option::setNumber("Mesh.Binary", 0);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
}

class PointTable {
 public:
  explicit PointTable(double eps) : eps_(eps) {}
  int get(Vec2 p) {
    for (const auto& [q, tag] : pts_)
      if (scene::norm(q - p) <= eps_) return tag;
    const int tag = gmsh::model::geo::addPoint(p.x, p.y, 0.0);
    pts_.emplace_back(p, tag);
    return tag;
  }

 private:
  double eps_;
  std::vector<std::pair<Vec2, int>> pts_;
};

// The curves of the region's boundary loops, with their patches.
struct TaggedCurve {
  int tag = 0;
  Patch patch = Patch::body;
};

PlaneMesh read_plane(const std::vector<int>& surfaces, const std::vector<TaggedCurve>& curves) {
  PlaneMesh m;
  std::unordered_map<std::size_t, int> index;
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  for (const int surface : surfaces) {
    gmsh::model::mesh::getNodes(tags, coord, param, 2, surface, true, false);
    for (std::size_t i = 0; i < tags.size(); ++i)
      if (index.emplace(tags[i], static_cast<int>(m.nodes.size())).second)
        m.nodes.push_back({coord[3 * i], coord[3 * i + 1]});
  }
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> elems, nodes;
  for (const int surface : surfaces) {
    gmsh::model::mesh::getElements(types, elems, nodes, 2, surface);
    for (std::size_t t = 0; t < types.size(); ++t) {
      const int per = types[t] == kQuad ? 4 : types[t] == kTriangle ? 3 : 0;
      if (per == 0)
        throw scene::RunError("gmsh produced 2D elements of unexpected type " +
                              std::to_string(types[t]));
      for (std::size_t e = 0; e < elems[t].size(); ++e) {
        std::array<int, 4> c{-1, -1, -1, -1};
        for (int k = 0; k < per; ++k)
          c[static_cast<std::size_t>(k)] = index.at(nodes[t][e * per + k]);
        m.cells.push_back(c);
      }
      (per == 4 ? m.quads : m.triangles) += static_cast<long>(elems[t].size());
    }
  }
  // The patch of every boundary edge comes from the curve gmsh meshed it on:
  // exact for arcs and segments alike, with no geometric test.
  for (const TaggedCurve& c : curves) {
    gmsh::model::mesh::getElements(types, elems, nodes, 1, c.tag);
    for (std::size_t t = 0; t < types.size(); ++t) {
      if (types[t] != kLine)
        throw scene::RunError("gmsh produced 1D elements of unexpected type " + std::to_string(types[t]));
      for (std::size_t e = 0; e < elems[t].size(); ++e)
        m.boundary.push_back({index.at(nodes[t][2 * e]), index.at(nodes[t][2 * e + 1]), c.patch});
    }
  }
  return m;
}

// A strip as a transfinite surface: every outline segment its own line
// (two nodes), the four corners named, so gmsh's transfinite interpolation
// puts node (i, j) on the straight column between the sides' nodes. Returns
// its curve loop; the surface is added to `surfaces`.
int add_strip(const ShockStrip& st, PointTable& points, std::vector<int>& surfaces) {
  const std::vector<Vec2> outline = st.outline();
  const std::size_t n = st.stations(), m = st.rows.size();
  std::vector<int> pts;
  for (const Vec2 p : outline) pts.push_back(points.get(p));
  std::vector<int> curves;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const int c = gmsh::model::geo::addLine(pts[k], pts[(k + 1) % pts.size()]);
    gmsh::model::geo::mesh::setTransfiniteCurve(c, 2);
    curves.push_back(c);
  }
  const int loop = gmsh::model::geo::addCurveLoop(curves);
  const int surface = gmsh::model::geo::addPlaneSurface({loop});
  const std::vector<int> corners{pts[0], pts[n - 1], pts[n - 1 + m - 1], pts[2 * (n - 1) + m - 1]};
  gmsh::model::geo::mesh::setTransfiniteSurface(surface, "Left", corners);
  gmsh::model::geo::mesh::setRecombine(2, surface);
  surfaces.push_back(surface);
  return loop;
}

// gmsh's own one-cell extrusion of the plane surfaces (the main surface
// first, then the strips) with the patches as physical groups: the
// gmshToFoam route, kept as the reference the direct writer is tested
// against. Strip outlines become internal faces (no patch).
void extrude_and_name(const std::vector<int>& plane, const std::vector<TaggedCurve>& boundary,
                      const std::vector<ShockStrip>& strips, double thickness) {
  gmsh::vectorpair bottoms;
  for (const int s : plane) bottoms.emplace_back(2, s);
  std::size_t strip_curves = 0;
  for (const ShockStrip& st : strips) strip_curves += st.outline().size();
  gmsh::vectorpair out;
  gmsh::model::geo::extrude(bottoms, 0.0, 0.0, thickness, out, {1}, {}, true);
  gmsh::model::geo::synchronize();
  const std::size_t main_entities = 2 + boundary.size() + strip_curves;
  const std::size_t strip_surfaces = plane.size() - 1;
  if (out.size() != main_entities + 2 * strip_surfaces + strip_curves)
    throw scene::RunError("gmsh extrusion returned " + std::to_string(out.size()) + " entities, expected " +
                          std::to_string(main_entities + 2 * strip_surfaces + strip_curves));
  std::vector<int> tops{out[0].second}, volumes{out[1].second};
  for (std::size_t k = 0, at = main_entities; k < strip_surfaces; ++k) {
    tops.push_back(out[at].second);
    volumes.push_back(out[at + 1].second);
    at += 2 + strips[k].outline().size();
  }
  std::map<Patch, std::vector<int>> by_patch;
  for (std::size_t i = 0; i < boundary.size(); ++i) by_patch[boundary[i].patch].push_back(out[2 + i].second);
  for (const auto& [patch, tags] : by_patch) {
    const int g = gmsh::model::addPhysicalGroup(2, tags);
    gmsh::model::setPhysicalName(2, g, patch_name(patch));
  }
  std::vector<int> front_back = plane;
  front_back.insert(front_back.end(), tops.begin(), tops.end());
  const int fb = gmsh::model::addPhysicalGroup(2, front_back);
  gmsh::model::setPhysicalName(2, fb, "frontAndBack");
  const int fluid = gmsh::model::addPhysicalGroup(3, volumes);
  gmsh::model::setPhysicalName(3, fluid, "fluid");
}

int add_curve(const BoundaryCurve& c, PointTable& points) {
  const int a = points.get(c.a), b = points.get(c.b);
  if (!c.is_arc) return gmsh::model::geo::addLine(a, b);
  const int centre = gmsh::model::geo::addPoint(c.center.x, c.center.y, 0.0);
  return gmsh::model::geo::addCircleArc(a, centre, b);
}

// The region as plane surfaces sharing the cuts (region_split.hpp), for
// gmsh to mesh on several threads. Adds the boundary curves to `boundary`.
std::vector<int> add_pieces(const RegionPieces& pieces, PointTable& points, std::vector<TaggedCurve>& boundary) {
  std::vector<int> plane;
  std::vector<std::pair<int, Vec2>> cuts(pieces.x.size());  // curve tag, start point
  for (const auto& loops : pieces.loops) {
    std::vector<int> loop_tags;
    for (const auto& loop : loops) {
      std::vector<int> curves;
      for (const PieceCurve& pc : loop) {
        if (pc.cut < 0) {
          curves.push_back(add_curve(pc.curve, points));
          boundary.push_back({curves.back(), pc.curve.patch});
          continue;
        }
        auto& [tag, start] = cuts[static_cast<std::size_t>(pc.cut)];
        if (tag == 0) {
          tag = add_curve(pc.curve, points);
          start = pc.curve.a;
        }
        curves.push_back(pc.curve.a == start ? tag : -tag);  // the other piece runs it backwards
      }
      loop_tags.push_back(gmsh::model::geo::addCurveLoop(curves));
    }
    plane.push_back(gmsh::model::geo::addPlaneSurface(loop_tags));
  }
  return plane;
}

PlaneMesh run(const FluidRegion& region, const SizeFunction& size,
              const std::vector<ShockStrip>& strips, const GmshJob& job) {
  gmsh::clear();
  gmsh::model::add("meshgen");
  set_options(job);
  PointTable points(kSamePoint * region.length_scale);
  std::vector<TaggedCurve> boundary;  // in the order gmsh reports lateral surfaces
  std::vector<int> plane;
  // Split only where nothing else cuts the region (strips are holes the cut
  // would cross) and gmsh's own extrusion is not asked for (it expects one
  // main surface).
  std::optional<RegionPieces> pieces;
  if (job.pieces > 1 && strips.empty() && job.extruded_msh_path.empty())
    pieces = split_region(region, size, job.pieces);
  if (pieces) {
    plane = add_pieces(*pieces, points, boundary);
  } else {
    std::vector<int> loop_tags;
    for (const auto& loop : region.loops) {
      std::vector<int> curves;
      for (const BoundaryCurve& c : loop) {
        curves.push_back(add_curve(c, points));
        boundary.push_back({curves.back(), c.patch});
      }
      loop_tags.push_back(gmsh::model::geo::addCurveLoop(curves));
    }
    // Strips are holes of the main surface and surfaces of their own; their
    // lateral faces after extrusion are internal (no patch).
    std::vector<int> strip_surfaces;
    for (const ShockStrip& st : strips) loop_tags.push_back(add_strip(st, points, strip_surfaces));
    plane.push_back(gmsh::model::geo::addPlaneSurface(loop_tags));
    plane.insert(plane.end(), strip_surfaces.begin(), strip_surfaces.end());
  }
  if (!job.extruded_msh_path.empty()) extrude_and_name(plane, boundary, strips, job.thickness);
  gmsh::model::geo::synchronize();

  gmsh::model::mesh::setSizeCallback([&size](int, int, double x, double y, double) { return size({x, y}); });
  gmsh::model::mesh::generate(job.extruded_msh_path.empty() ? 2 : 3);
  gmsh::model::mesh::removeSizeCallback();
  PlaneMesh m = read_plane(plane, boundary);
  if (!job.extruded_msh_path.empty()) gmsh::write(job.extruded_msh_path);
  gmsh::clear();
  m.pieces = static_cast<int>(pieces ? pieces->loops.size() : 1);
  return m;
}

PlaneMesh guarded(const std::function<PlaneMesh()>& mesh) {
  const std::lock_guard<std::mutex> lock(gmsh_mutex());
  ensure_initialized();
  try {
    return mesh();
  } catch (const scene::RunError&) {
    gmsh::model::mesh::removeSizeCallback();  // it refers to `size`, which is going away
    gmsh::clear();
    throw;
  } catch (...) {
    std::string last;
    gmsh::logger::getLastError(last);
    gmsh::model::mesh::removeSizeCallback();
    gmsh::clear();
    throw scene::RunError("gmsh failed: " + (last.empty() ? std::string("unknown error") : last));
  }
}

}  // namespace

PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeField& size, const GmshJob& job) {
  return guarded([&] {
    return run(
        region, [&size](Vec2 p) { return size(p); }, {}, job);
  });
}

PlaneMesh mesh_with_gmsh(const FluidRegion& region, const SizeFunction& size,
                         const std::vector<ShockStrip>& strips, const GmshJob& job) {
  return guarded([&] { return run(region, size, strips, job); });
}

}  // namespace meshgen
