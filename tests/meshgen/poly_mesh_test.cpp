// The direct polyMesh writer against the gmshToFoam route on the same grid
// (real gmsh + OpenFOAM): gmsh meshes once, extruding and writing its own
// .msh as well; gmshToFoam converts that, meshgen's writer the plane mesh.
// Same cells, volumes, patches and patch areas, both pass checkMesh; so the
// writer cannot drift from what gmshToFoam made of gmsh's extrusion.
#include "poly_mesh.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "band_strip.hpp"
#include "extruded_layer.hpp"
#include "foam_export.hpp"
#include "gmsh_mesher.hpp"
#include "meshgen/fluid_region.hpp"
#include "meshgen/size_field.hpp"
#include "msh_file.hpp"
#include "msh_writer.hpp"
#include "poly_mesh_file.hpp"
#include "scene/scene.hpp"
#include "shock_fixtures.hpp"

namespace {

namespace fs = std::filesystem;

// Both routes carry the same points exactly (gmshToFoam writes 17 digits):
// totals agree to round-off in the sums, cells to round-off in the
// divergence-theorem sums (coordinates ~20 cell sizes from the origin).
constexpr double kTotalTolerance = 1e-12;
constexpr double kCellTolerance = 1e-10;
constexpr double kAreaTolerance = 1e-12;
// Coarse sizes (body lengths): a few thousand cells.
constexpr double kH = 0.05, kHMin = 0.01, kHMax = 0.06, kGrowth = 1.2;
constexpr double kAnisotropy = 10.0;
constexpr double kThickness = 0.07;  // any value: both routes extrude the same

struct Grid {
  meshgen::PlaneMesh plane;
  bool symmetric = false;
};

// gmsh (extruding, as the gmshToFoam route needs), in this process.
Grid mesh_case(const std::string& name, bool strips, const std::string& msh) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
  const meshgen::FluidRegion region = meshgen::make_fluid_region(s);
  const double L = region.length_scale;
  meshgen::GmshJob job;
  job.thickness = kThickness;
  job.extruded_msh_path = msh;
  Grid g;
  g.symmetric = region.domain.symmetric;
  if (!strips) {
    g.plane = meshgen::mesh_with_gmsh(region, meshgen::SizeField(kH * L), job);
    return g;
  }
  const std::vector<scene::Vec2> curve = meshgen_test::predicted_shock(s);
  const std::vector<double> width(curve.size(), 3.0 * kHMin * L);
  const auto runs = meshgen::clip_shock(curve, width, region, 0.25 * kHMin * L);
  meshgen::SizeParams p;
  p.h_min = kHMin * L;
  p.h_max = kHMax * L;
  p.h_body = kHMax * L;
  p.growth = kGrowth;
  const meshgen::BandLayout band =
      meshgen::layout_strips(runs, region, {p.h_min, kAnisotropy, p.h_max, p.growth});
  EXPECT_FALSE(band.strips.empty()) << name << ": no strip laid";
  const meshgen::BandSize size(p, band, region.body.polyline);
  g.plane = meshgen::mesh_with_gmsh(
      region, [&size](scene::Vec2 q) { return size(q); }, band.strips, job);
  return g;
}

void expect_check_mesh_passes(const std::string& dir, long cells) {
  const meshgen::CheckMeshReport r = meshgen::run_check_mesh(dir);
  EXPECT_TRUE(r.ok || r.warnings_only) << dir << ": " << r.failures;
  EXPECT_EQ(r.cells, cells) << dir;
}

void compare_routes(const std::string& name, bool strips) {
  const std::string dir = meshgen_test::fresh_dir("poly_" + name + (strips ? "_strips" : ""));
  const std::string ref = dir + "/gmshToFoam", direct = dir + "/direct";
  fs::create_directories(ref);
  const Grid g = mesh_case(name, strips, ref + "/mesh.msh");
  const std::vector<meshgen::FoamPatch> patches = meshgen::foam_patches(g.symmetric);

  meshgen::write_control_dict(ref);
  meshgen::run_gmsh_to_foam(ref);
  std::map<std::string, std::string> types;
  for (const auto& p : patches) types[p.name] = p.type;
  meshgen::set_patch_types(ref, types);

  meshgen::write_control_dict(direct);
  const meshgen::ExtrudedLayer layer = meshgen::extrude_layer(g.plane);
  meshgen::write_poly_mesh(g.plane, layer, kThickness, patches, direct);
  meshgen::write_extruded_msh(g.plane, layer, kThickness, direct + "/mesh.msh");

  const auto a = meshgen_test::read_poly_mesh(ref), b = meshgen_test::read_poly_mesh(direct);
  const long cells = static_cast<long>(g.plane.cells.size());
  ASSERT_EQ(a.cells, cells) << name;
  ASSERT_EQ(b.cells, cells) << name;
  EXPECT_EQ(a.points.size(), b.points.size()) << name;
  EXPECT_EQ(a.faces.size(), b.faces.size()) << name;
  EXPECT_EQ(a.neighbour.size(), b.neighbour.size()) << name;

  // Every cell volume positive, and the same volumes on both routes.
  std::vector<double> va = meshgen_test::cell_volumes(a), vb = meshgen_test::cell_volumes(b);
  double ta = 0, tb = 0;
  for (const double v : vb) EXPECT_GT(v, 0.0) << name;
  for (const double v : va) ta += v;
  for (const double v : vb) tb += v;
  EXPECT_NEAR(tb / ta, 1.0, kTotalTolerance) << name;
  std::sort(va.begin(), va.end());
  std::sort(vb.begin(), vb.end());
  for (std::size_t i = 0; i < va.size(); ++i)
    ASSERT_NEAR(vb[i], va[i], kCellTolerance * va[i]) << name << " cell " << i;

  // Same patches, types, order, face counts and areas.
  ASSERT_EQ(a.patches.size(), b.patches.size()) << name;
  for (std::size_t p = 0; p < a.patches.size(); ++p) {
    EXPECT_EQ(b.patches[p].name, a.patches[p].name) << name;
    EXPECT_EQ(b.patches[p].type, a.patches[p].type) << name;
    EXPECT_EQ(b.patches[p].faces, a.patches[p].faces) << name << " " << a.patches[p].name;
    EXPECT_GT(b.patches[p].faces, 0) << name << " " << a.patches[p].name;
    const double area = meshgen_test::patch_area(a, a.patches[p]);
    EXPECT_NEAR(meshgen_test::patch_area(b, b.patches[p]), area, kAreaTolerance * area)
        << name << " " << a.patches[p].name;
  }
  // OpenFOAM's order: internal faces by owner, then neighbour; owner below neighbour.
  for (std::size_t f = 0; f < b.neighbour.size(); ++f) {
    ASSERT_LT(b.owner[f], b.neighbour[f]) << name << " face " << f;
    if (f > 0) {
      ASSERT_TRUE(b.owner[f - 1] < b.owner[f] ||
                  (b.owner[f - 1] == b.owner[f] && b.neighbour[f - 1] < b.neighbour[f]))
          << name << " face " << f;
    }
  }
  // z from 0 to the thickness, as gmshToFoam's.
  double zmin = 1e300, zmax = -1e300;
  for (const auto& p : b.points) {
    zmin = std::min(zmin, p[2]);
    zmax = std::max(zmax, p[2]);
  }
  EXPECT_EQ(zmin, 0.0);
  EXPECT_EQ(zmax, kThickness);

  expect_check_mesh_passes(ref, cells);
  expect_check_mesh_passes(direct, cells);

  // meshgen's mesh.msh: the elements gmsh's extrusion wrote, by type and physical name.
  const auto count = [](const std::string& path) {
    const meshgen_test::MshFile f = meshgen_test::read_msh(path);
    std::map<int, std::string> name_of;
    for (const auto& [n, tag] : f.physical)
      name_of[tag] = n;  // tags per dimension: 2D and 3D differ by type
    std::map<std::pair<int, std::string>, long> out;
    for (const auto& e : f.elements) {
      const bool volume = meshgen_test::is_volume(e);
      std::string group;
      for (const auto& [n, tag] : f.physical)
        if (tag == e.tags.at(0) && ((n == "fluid") == volume)) group = n;
      ++out[{e.type, group}];
    }
    return out;
  };
  EXPECT_EQ(count(direct + "/mesh.msh"), count(ref + "/mesh.msh")) << name;
}

}  // namespace

TEST(PolyMesh, WedgeMatchesGmshToFoam) {
  compare_routes("wedge_M3_10", false);
}
TEST(PolyMesh, DiscArcsMatchGmshToFoam) {
  compare_routes("disc_M4", false);
}
TEST(PolyMesh, ApolloMatchesGmshToFoam) {
  compare_routes("apollo_M5", false);
}
TEST(PolyMesh, ShockStripsMatchGmshToFoam) {
  compare_routes("wedge_M3_10", true);
}

// The region cut into pieces for gmsh's threads (region_split.hpp): the cut's
// edges become internal faces, the grid covers the region exactly (a wedge
// region is a polygon: its area is exact) and passes checkMesh.
TEST(PolyMesh, SplitRegionIsOneClosedGrid) {
  const std::string dir = meshgen_test::fresh_dir("poly_split");
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const meshgen::FluidRegion region = meshgen::make_fluid_region(s);
  meshgen::GmshJob job;
  job.thickness = kThickness;
  job.threads = 2;
  job.pieces = 3;
  const meshgen::PlaneMesh plane =
      meshgen::mesh_with_gmsh(region, meshgen::SizeField(kH * region.length_scale), job);
  ASSERT_EQ(plane.pieces, 3);
  meshgen::write_control_dict(dir);
  meshgen::write_poly_mesh(plane, meshgen::extrude_layer(plane), kThickness,
                           meshgen::foam_patches(true), dir);
  const auto m = meshgen_test::read_poly_mesh(dir);
  double volume = 0.0;
  for (const double v : meshgen_test::cell_volumes(m)) {
    EXPECT_GT(v, 0.0);
    volume += v;
  }
  double area = 0.0;  // the region's outer loop (a wedge region has no hole)
  ASSERT_EQ(region.loops.size(), 1u);
  for (const auto& c : region.loops.front()) area += 0.5 * (c.a.x * c.b.y - c.b.x * c.a.y);
  EXPECT_NEAR(volume / (area * kThickness), 1.0, kTotalTolerance);
  expect_check_mesh_passes(dir, static_cast<long>(plane.cells.size()));
}
