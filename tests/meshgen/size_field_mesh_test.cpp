// meshgen --size-field with real gmsh and OpenFOAM: cells follow the
// lattice's h; a bad size field is refused with exit 2 naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "scene/io.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "msh_file.hpp"
#include "shock_fixtures.hpp"

namespace {

// Fine and coarse halves of the size field (body lengths).
constexpr double kFine = 0.02, kCoarse = 0.08;
// Cells per unit area scale as 1/h^2: (kCoarse / kFine)^2 = 16 between the
// halves. Unstructured cells are not exactly h (and the jump between the
// halves is spread over a lattice cell), so the test asks for half of it.
constexpr double kMinDensityRatio = 8.0;
// Margin (body lengths) kept from the jump and from the body when counting.
constexpr double kMargin = 0.15;

using test_support::CliRun;

CliRun run_meshgen(const std::string& args) {
  return test_support::run_cli(test_support::stage_exe("meshgen"), args);
}

// A lattice over the scene's domain: kFine left of x_split, kCoarse right.
scene::Lattice halves(const scene::Domain& d, double x_split) {
  scene::Lattice lat = scene::domain_lattice(d, 60, 40);
  auto& h = lat.add("h");
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) h[lat.index(i, j)] = lat.xc(i) < x_split ? kFine : kCoarse;
  return lat;
}

// Centroids (x, y) of the volume cells of a gmsh 2.2 ASCII file (hexahedra, prisms).
std::vector<scene::Vec2> cell_centroids(const std::string& msh) {
  const meshgen_test::MshFile f = meshgen_test::read_msh(msh);
  std::vector<scene::Vec2> out;
  for (const auto& e : f.elements) {
    if (!meshgen_test::is_volume(e)) continue;
    scene::Vec2 c;
    for (const std::size_t node : e.nodes) c += f.nodes.at(node);
    out.push_back(c / static_cast<double>(e.nodes.size()));
  }
  return out;
}

}  // namespace

TEST(SizeFieldMesh, CellsConcentrateWhereTheFieldIsSmall) {
  const std::string scene_path = meshgen_test::case_path("wedge_M3_10");
  const scene::Scene s = scene::load_scene(scene_path);
  const scene::Domain d = scene::scene_domain(s);
  const double x_split = 0.5 * (d.xmin + d.xmax);
  const std::string dir = meshgen_test::fresh_dir("size_field");
  const std::string field = dir + "/size.vti";
  scene::write_vti(halves(d, x_split), field);
  const CliRun r =
      run_meshgen(scene_path + " --size-field " + field + " --h-min " + std::to_string(kFine) +
                  " --h-max " + std::to_string(kCoarse) + " --out " + dir + "/mesh");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto sum = nlohmann::json::parse(scene::read_file(dir + "/mesh/summary.json"));
  EXPECT_EQ(sum.value("kind", ""), "adapted");
  EXPECT_EQ(sum.value("size_field", ""), field);
  EXPECT_TRUE(sum.value("check_mesh_ok", false));
  // Count cells per unit area in two rectangles above the body (the wedge
  // face reaches y = sin 10 deg), clear of the jump.
  const double y0 = 0.2 + kMargin;
  ASSERT_LT(y0, d.ymax - kMargin);
  double left = 0, right = 0;
  for (const scene::Vec2 c : cell_centroids(dir + "/mesh/mesh.msh")) {
    if (c.y < y0) continue;
    if (c.x < x_split - kMargin) left += 1;
    if (c.x > x_split + kMargin) right += 1;
  }
  const double area_left = (x_split - kMargin - d.xmin) * (d.ymax - y0);
  const double area_right = (d.xmax - x_split - kMargin) * (d.ymax - y0);
  ASSERT_GT(right, 0);
  const double ratio = (left / area_left) / (right / area_right);
  EXPECT_GT(ratio, kMinDensityRatio) << left << " cells left, " << right << " right";
  // Cells left: about area / kFine^2 (quads), within the mesher's spread.
  EXPECT_GT(left, 0.5 * area_left / (kFine * kFine));
  EXPECT_LT(left, 2.0 * area_left / (kFine * kFine));
}

TEST(SizeFieldMesh, BadSizeFieldsExitTwoNamingTheFile) {
  const std::string scene_path = meshgen_test::case_path("wedge_M3_10");
  const scene::Domain d = scene::scene_domain(scene::load_scene(scene_path));
  const std::string dir = meshgen_test::fresh_dir("size_field_bad");
  const auto expect_refused = [&](const std::string& file, const std::string& words) {
    const CliRun r = run_meshgen(scene_path + " --size-field " + file + " --out " + dir + "/mesh");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/mesh")) << "nothing written for " << file;
  };
  expect_refused(dir + "/absent.vti", "no such file");

  scene::Lattice no_h = halves(d, 0.0);
  no_h.fields["size"] = no_h.fields["h"];
  no_h.fields.erase("h");
  scene::write_vti(no_h, dir + "/no_h.vti");
  expect_refused(dir + "/no_h.vti", "no field 'h'");

  scene::Lattice nan = halves(d, 0.0);
  nan.fields["h"][7] = std::nan("");
  scene::write_vti(nan, dir + "/nan.vti");
  expect_refused(dir + "/nan.vti", "finite and positive");

  scene::Lattice zero = halves(d, 0.0);
  zero.fields["h"][3] = 0.0;
  scene::write_vti(zero, dir + "/zero.vti");
  expect_refused(dir + "/zero.vti", "finite and positive");

  {
    std::ofstream junk(dir + "/junk.vti");
    junk << "not a lattice\n";
  }
  expect_refused(dir + "/junk.vti", "not a lattice .vti file");

  // A size field is a grid of its own: not with --shock or --uniform.
  scene::write_vti(halves(d, 0.0), dir + "/good.vti");
  const CliRun both = run_meshgen(scene_path + " --size-field " + dir +
                                  "/good.vti --uniform --out " + dir + "/mesh");
  EXPECT_EQ(both.code, 2) << both.err;
  EXPECT_NE(both.err.find("give one of --shock, --size-field and --uniform"), std::string::npos)
      << both.err;
}
