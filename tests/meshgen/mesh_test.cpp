// Real gmsh + OpenFOAM meshes of every case-study body, at coarse sizes.
#include "meshgen/mesh.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>
#include <vector>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "shock_fixtures.hpp"

namespace {

// Coarse sizes (body lengths) to keep the suite quick.
constexpr double kTestHMin = 0.02, kTestHMax = 0.1;
// Unstructured cells are never exactly the requested size: a cell in the
// band may reach this much above h_min (mean edge length; measured up to
// 1.24 h_min on these grids with Delaunay + simple recombination).
constexpr double kBandSizeTolerance = 0.35;
// With shock-aligned strips (attached wedges) band cells are long along the
// shock; across it they are at most this many h_min thick (strip rows
// h_min, the isotropic band cells near the apex up to ~1.7 h_min, as in
// anisotropy_test.cpp).
constexpr double kMaxBandThicknessCells = 2.0;
// Uniform grids: every cell within this factor of the requested size.
constexpr double kUniformSpread = 2.0;
// The mesher's count against meshgen's estimate (1.5 quads per h^2 of the
// size field's integral; measured 0.98-1.05 on the case studies' grids).
constexpr double kEstimateLow = 0.75, kEstimateHigh = 1.33;
constexpr double kTargetTolerance = 0.10;  // meshgen's stated target-count tolerance
const char* const kCases[] = {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"};

nlohmann::json read_summary(const std::string& dir) {
  return nlohmann::json::parse(scene::read_file(dir + "/summary.json"));
}

// name -> type from constant/polyMesh/boundary.
std::map<std::string, std::string> patch_types(const std::string& dir) {
  const std::string text = scene::read_file(dir + "/constant/polyMesh/boundary");
  std::map<std::string, std::string> out;
  const std::regex entry(R"((\w+)\s*\{\s*type\s+(\w+);)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    out[(*it)[1].str()] = (*it)[2].str();
  return out;
}

meshgen::MeshRequest clustered_request(const scene::Scene& s, double ci_body_lengths) {
  meshgen::MeshRequest r;
  r.shock_curve = meshgen_test::predicted_shock(s);
  r.shock_ci.assign(r.shock_curve.size(), ci_body_lengths * scene::body_length(*s.body));
  r.h_min = kTestHMin;
  r.h_max = kTestHMax;
  return r;
}

void expect_good_case(const std::string& dir, const meshgen::MeshResult& res) {
  EXPECT_TRUE(res.check_mesh_ok) << res.details.value("check_mesh_failures", "");
  EXPECT_GT(res.max_non_orthogonality, 0.0);
  EXPECT_GT(res.max_skewness, 0.0);
  for (const char* f : {"mesh.msh", "constant/polyMesh/faces", "summary.json", "log.checkMesh", "mesh.png",
                        "mesh_zoom.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  const nlohmann::json j = read_summary(dir);
  for (const char* k : {"cells", "min_cell_size", "max_cell_size", "kind", "max_non_orthogonality", "max_skewness",
                        "check_mesh_ok"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["cells"].get<long>(), res.cells);
  const double est = j["estimated_cells"].get<double>();
  EXPECT_GT(static_cast<double>(res.cells), kEstimateLow * est);
  EXPECT_LT(static_cast<double>(res.cells), kEstimateHigh * est);
  const auto types = patch_types(dir);
  EXPECT_EQ(types, (std::map<std::string, std::string>{{"inlet", "patch"},
                                                       {"outlet", "patch"},
                                                       {"top", "patch"},
                                                       {"bottom", "symmetryPlane"},
                                                       {"body", "wall"},
                                                       {"frontAndBack", "empty"}}));
}

}  // namespace

TEST(Mesh, EveryCaseMeshesClusteredAndUniform) {
  for (const char* name : kCases) {
    SCOPED_TRACE(name);
    const scene::Scene s = scene::load_scene(meshgen_test::case_path(name));
    const double L = scene::body_length(*s.body);
    const std::string cdir = meshgen_test::fresh_dir(std::string("clustered_") + name);
    const meshgen::MeshResult c = meshgen::generate_mesh(s, clustered_request(s, 0.03), cdir);
    EXPECT_EQ(c.kind, "clustered");
    expect_good_case(cdir, c);
    const nlohmann::json cj = read_summary(cdir);
    ASSERT_GT(cj["band_cells"].get<long>(), 0);
    if (cj["band_strips"].get<long>() > 0)  // long along the shock by design: h_min across it
      EXPECT_LE(cj["band_max_thickness"].get<double>(), kMaxBandThicknessCells * kTestHMin * L);
    else
      EXPECT_LE(cj["band_max_cell_size"].get<double>(), kTestHMin * L * (1.0 + kBandSizeTolerance));
    EXPECT_LE(c.max_cell_size, kTestHMax * L * kUniformSpread);

    meshgen::MeshRequest u;
    u.uniform = true;
    u.h_min = kTestHMin;
    const std::string udir = meshgen_test::fresh_dir(std::string("uniform_") + name);
    const meshgen::MeshResult un = meshgen::generate_mesh(s, u, udir);
    EXPECT_EQ(un.kind, "uniform");
    expect_good_case(udir, un);
    EXPECT_GT(un.min_cell_size, kTestHMin * L / kUniformSpread);
    EXPECT_LT(un.max_cell_size, kTestHMin * L * kUniformSpread);
    // Same resolution at the shock for a fraction of the cells.
    EXPECT_LT(2 * c.cells, un.cells);
  }
}

TEST(Mesh, WiderUncertaintyWidensTheBand) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M4_15"));
  const auto narrow = meshgen::generate_mesh(s, clustered_request(s, 0.0), meshgen_test::fresh_dir("ci_narrow"));
  const auto wide = meshgen::generate_mesh(s, clustered_request(s, 0.1), meshgen_test::fresh_dir("ci_wide"));
  EXPECT_GT(wide.details["band_half_width_max"].get<double>(), narrow.details["band_half_width_max"].get<double>());
  EXPECT_GT(wide.details["band_cells"].get<long>(), narrow.details["band_cells"].get<long>());
  EXPECT_GT(wide.cells, narrow.cells);
}

TEST(Mesh, ShockThroughTheBodyIsClippedNotFatal) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("disc_M4"));
  meshgen::MeshRequest r = clustered_request(s, 0.0);
  r.shock_curve = {{-0.8, 0.2}, {0.0, 0.2}, {0.3, 0.0}, {0.5, 3.0}};  // through the disc, out of the domain
  r.shock_ci.clear();
  const std::string dir = meshgen_test::fresh_dir("through_body");
  const meshgen::MeshResult res = meshgen::generate_mesh(s, r, dir);
  EXPECT_TRUE(res.check_mesh_ok);
  EXPECT_GE(res.details["shock_runs"].get<long>(), 1);
}

TEST(Mesh, TargetCellCountIsMetWithinTenPercent) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("apollo_M5"));
  for (const bool uniform : {false, true}) {
    meshgen::MeshRequest r = clustered_request(s, 0.02);
    r.h_min.reset();
    r.h_max.reset();
    r.uniform = uniform;
    r.target_cells = 4000;
    const auto res = meshgen::generate_mesh(s, r, meshgen_test::fresh_dir(uniform ? "target_u" : "target_c"));
    EXPECT_NEAR(static_cast<double>(res.cells), 4000.0, kTargetTolerance * 4000.0) << (uniform ? "uniform" : "clustered");
  }
}

TEST(Mesh, SameInputSameGrid) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const auto a = meshgen::generate_mesh(s, clustered_request(s, 0.02), meshgen_test::fresh_dir("det_a"));
  const auto b = meshgen::generate_mesh(s, clustered_request(s, 0.02), meshgen_test::fresh_dir("det_b"));
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_DOUBLE_EQ(a.min_cell_size, b.min_cell_size);
}

// gmsh's 2D meshing on two threads depends on how they interleave (the disc's
// 54k-cell uniform grid came out 54094 or 54205 cells, 1 run in 12 with a second
// process on the core), so meshgen meshes the pieces of a split region one
// after another. A split grid meshed while busy threads compete for every
// core must come out bit for bit the same each time.
TEST(Mesh, SplitGridIsBitForBitTheSameUnderLoad) {
  constexpr double kSplitH = 0.025;  // disc radii: ~35k cells, two pieces
  constexpr int kRepeats = 6;
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("disc_M4"));
  meshgen::MeshRequest r;
  r.uniform = true;
  r.h_min = r.h_max = kSplitH;
  std::atomic<bool> stop{false};
  std::vector<std::thread> busy;
  for (unsigned i = 0; i < std::max(2u, std::thread::hardware_concurrency()); ++i)
    busy.emplace_back([&stop] {
      volatile unsigned long spin = 0;
      while (!stop.load(std::memory_order_relaxed)) spin = spin + 1;
    });
  std::vector<std::string> points;
  std::vector<long> cells, pieces;
  for (int k = 0; k < kRepeats; ++k) {
    const std::string dir = meshgen_test::fresh_dir("split_load_" + std::to_string(k));
    cells.push_back(meshgen::generate_mesh(s, r, dir).cells);
    points.push_back(scene::read_file(dir + "/constant/polyMesh/points"));
    pieces.push_back(read_summary(dir)["gmsh_pieces"].get<long>());
  }
  stop = true;
  for (auto& t : busy) t.join();
  ASSERT_GE(pieces[0], 2) << "the grid must be split for the test to mean anything";
  for (int k = 1; k < kRepeats; ++k) {
    EXPECT_EQ(cells[k], cells[0]) << "repeat " << k;
    EXPECT_TRUE(points[k] == points[0]) << "repeat " << k << ": points differ";
  }
}

TEST(Mesh, BadRequestsAreClearErrors) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  meshgen::MeshRequest none;
  try {
    (void)meshgen::generate_mesh(s, none, meshgen_test::fresh_dir("no_shock"));
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a clustered grid needs a shock curve"), std::string::npos) << e.what();
  }
  meshgen::MeshRequest outside;
  outside.shock_curve = {{5.0, 5.0}, {6.0, 6.0}};
  try {
    (void)meshgen::generate_mesh(s, outside, meshgen_test::fresh_dir("outside"));
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the shock curve lies wholly outside the flow region"), std::string::npos)
        << e.what();
  }
}

TEST(Mesh, AsymmetricBodiesWhollyInsideOrThroughTheOutlet) {
  // Off-axis triangle: wholly inside a given domain (the body is a hole), and
  // with the default domain (its rear vertex on the outflow plane).
  const std::string body = "name: tri\nbody: {kind: polygon, points: [[0, 0.1], [1, 0.3], [0.8, -0.4]]}\n"
                           "freestream: {mach: 3.0}\nmesh: {h_min: 0.06, h_max: 0.2}\n";
  const scene::Scene hole = scene::parse_scene(body + "domain: {xmin: -1, xmax: 2, ymin: -1.5, ymax: 1.5}\n");
  const scene::Scene cut = scene::parse_scene(body);
  for (const scene::Scene* s : {&hole, &cut}) {
    meshgen::MeshRequest u;
    u.uniform = true;
    const std::string dir = meshgen_test::fresh_dir(s == &hole ? "asym_hole" : "asym_cut");
    const meshgen::MeshResult res = meshgen::generate_mesh(*s, u, dir);
    EXPECT_TRUE(res.check_mesh_ok) << dir;
    const auto types = patch_types(dir);
    EXPECT_EQ(types.at("bottom"), "patch");  // far field, not a symmetry plane
    EXPECT_EQ(types.at("body"), "wall");
    EXPECT_EQ(types.size(), 6u);
  }
}
