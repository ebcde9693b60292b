// mesh.anisotropy: shock-aligned strips of long, thin quads in the shock
// band (real gmsh + OpenFOAM checkMesh), the isotropic grid untouched at 1,
// and bad values refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_run.hpp"
#include "gmsh_child.hpp"
#include "meshgen/mesh.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "shock_fixtures.hpp"

namespace {

using test_support::expect_refusal;
using test_support::write_scene;

// Body lengths: coarse, yet fine enough for a strip (half-width ~9 h_min at
// anisotropy 10) to fit between the wedge and the domain's exits.
constexpr double kHMin = 0.01, kHMax = 0.06;
constexpr double kAnisotropy = 10.0;
// On a straight oblique shock the strip's cells reach the requested aspect
// (measured 9.2); at least this much is asserted.
constexpr double kMinAspect = 4.0;
// Band cells are at most this many h_min thick across the shock: the strip's
// rows are h_min or thinner, the isotropic band cells near the wedge tip
// (where no strip fits) reach about 1.7 h_min as on today's grids.
constexpr double kMaxThicknessCells = 2.0;
// checkMesh flags non-orthogonality above 70 deg; rhoCentralFoam (explicit,
// no non-orthogonal correctors) runs on these grids, kept below this.
constexpr double kMaxNonOrthogonality = 65.0;
// The strips' rows are h_min thick or, where ceil(w / h_min) rows share a
// half-width w of a few h_min, a little thinner; the grid's smallest cell
// (mean edge length) stays within this fraction of the isotropic grid's.
constexpr double kMinRowFraction = 0.5;
// The strips replace most band cells: at most this fraction remains.
constexpr double kMaxBandCellFraction = 0.8;
// meshgen's estimate before gmsh (strips counted exactly, the isotropic grid
// round them integrated) against the grid gmsh made: the isotropic grids'
// tolerance (mesh_test.cpp); the isotropic band's estimate was about 2x high.
constexpr double kEstimateLow = 0.75, kEstimateHigh = 1.33;

nlohmann::json summary(const std::string& dir) {
  return nlohmann::json::parse(scene::read_file(dir + "/summary.json"));
}

meshgen::MeshRequest wedge_request(const scene::Scene& s) {
  meshgen::MeshRequest r;
  r.shock_curve = meshgen_test::predicted_shock(s);
  r.shock_ci.assign(r.shock_curve.size(), 0.5 * kHMin * scene::body_length(*s.body));
  r.h_min = kHMin;
  r.h_max = kHMax;
  return r;
}

scene::Scene wedge_with(double anisotropy) {
  scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  s.mesh.anisotropy = anisotropy;
  return s;
}

}  // namespace

TEST(Anisotropy, StraightObliqueShockGetsLongThinBandCells) {
  const std::string iso_dir = meshgen_test::fresh_dir("aniso_iso");
  const std::string aniso_dir = meshgen_test::fresh_dir("aniso_10");
  const scene::Scene iso = wedge_with(1.0), aniso = wedge_with(kAnisotropy);
  const meshgen::MeshResult a = meshgen::generate_mesh(iso, wedge_request(iso), iso_dir);
  const meshgen::MeshResult b = meshgen::generate_mesh(aniso, wedge_request(aniso), aniso_dir);
  const nlohmann::json ja = summary(iso_dir), jb = summary(aniso_dir);

  EXPECT_TRUE(b.check_mesh_ok) << jb.value("check_mesh_failures", "");
  EXPECT_LT(b.max_non_orthogonality, kMaxNonOrthogonality);
  EXPECT_EQ(jb["anisotropy"].get<double>(), kAnisotropy);
  EXPECT_GE(jb["band_strips"].get<long>(), 1);
  EXPECT_GT(jb["band_strip_cells"].get<long>(), 0);
  EXPECT_GE(jb["band_max_aspect_ratio"].get<double>(), kMinAspect);
  EXPECT_GT(jb["band_mean_aspect_ratio"].get<double>(), ja["band_mean_aspect_ratio"].get<double>());
  const double h_min = jb["h_min"].get<double>();
  EXPECT_LE(jb["band_max_thickness"].get<double>(), kMaxThicknessCells * h_min);
  EXPECT_LT(static_cast<double>(jb["band_cells"].get<long>()),
            kMaxBandCellFraction * static_cast<double>(ja["band_cells"].get<long>()));
  EXPECT_LT(b.cells, a.cells);
  const double estimate = jb["estimated_cells"].get<double>();
  EXPECT_GT(static_cast<double>(b.cells), kEstimateLow * estimate);
  EXPECT_LT(static_cast<double>(b.cells), kEstimateHigh * estimate);
  // The isotropic grid has no strips, and its band cells stay near square.
  EXPECT_EQ(ja["band_strips"].get<long>(), 0);
  EXPECT_LT(ja["band_max_aspect_ratio"].get<double>(), kMinAspect);
}

TEST(Anisotropy, AttachedWedgeDefaultsToStripsAndOneKeepsTheBandIsotropic) {
  const std::string dir = meshgen_test::fresh_dir("aniso_default");
  const std::string shock = dir + "/shock.csv";
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  meshgen_test::write_shock_csv(shock, meshgen_test::predicted_shock(s), 0.5 * kHMin);
  for (const char* sub : {"/plain", "/one"}) std::filesystem::create_directories(dir + sub);
  const std::string base =
      "body: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n";
  const std::string sizes = "h_min: " + std::to_string(kHMin) + ", h_max: " + std::to_string(kHMax);
  const std::string plain = write_scene(dir + "/plain", base + "mesh: {" + sizes + "}\n");
  const std::string one =
      write_scene(dir + "/one", base + "mesh: {" + sizes + ", anisotropy: 1}\n");
  const auto meshgen = [](const std::string& args) {
    return test_support::run_cli(test_support::stage_exe("meshgen"), args);
  };
  ASSERT_EQ(meshgen(plain + " --shock " + shock + " --out " + dir + "/a").code, 0);
  ASSERT_EQ(meshgen(one + " --shock " + shock + " --out " + dir + "/b").code, 0);
  const nlohmann::json ja = summary(dir + "/a"), jb = summary(dir + "/b");
  EXPECT_EQ(ja["anisotropy"].get<double>(), scene::kStraightShockAnisotropy);
  EXPECT_GE(ja["band_strips"].get<long>(), 1);
  EXPECT_EQ(jb["anisotropy"].get<double>(), 1.0);
  EXPECT_EQ(jb["band_strips"].get<long>(), 0);
  EXPECT_LT(jb["band_max_aspect_ratio"].get<double>(), kMinAspect);
  // The strips' rows are never thinner than the isotropic band's cells
  // (mean edge length, so a square h_min cell reads about h_min).
  EXPECT_GE(ja["min_cell_size"].get<double>(), kMinRowFraction * jb["min_cell_size"].get<double>());
}

// A granular bow shock is a noisy polyline whose direction can swing between
// stations more than its smoothed curvature says: on this recorded one
// (apollo_M5's `pipeline run`, its band half-widths as the pipeline widened
// them) a wide strip folded its outer rows near the axis and gmsh's grid
// overlapped itself. Strips now stop where their quads would fold.
TEST(Anisotropy, ANoisyBowShockMeshesWithStripsThatDoNotFold) {
  const std::string dir = meshgen_test::fresh_dir("aniso_bow");
  scene::Scene s = scene::load_scene(meshgen_test::case_path("apollo_M5"));
  s.mesh.anisotropy = kAnisotropy;
  meshgen::MeshRequest r = meshgen::request_from_shock_csv(
      std::string(SOURCE_DIR) + "/tests/data/apollo_M5_bow_shock_band.csv");
  constexpr double kBowHMin = 0.02, kBowHMax = 0.1;  // the case study's finest clustered level
  r.h_min = kBowHMin;
  r.h_max = kBowHMax;
  const meshgen::MeshResult m = meshgen::generate_mesh(s, r, dir);
  const nlohmann::json j = summary(dir);
  EXPECT_TRUE(m.check_mesh_ok) << j.value("check_mesh_failures", "");
  EXPECT_LT(m.max_non_orthogonality, kMaxNonOrthogonality);
  EXPECT_GE(j["band_strips"].get<long>(), 1);
  EXPECT_GE(j["band_max_aspect_ratio"].get<double>(), kMinAspect);
}

// A granular wedge shock (wedge_M3_10's `pipeline studies` run) whose ci
// more than doubles along the shock is laid as several strips; near the
// outlet the end columns of two neighbours tilted towards each other and
// crossed between the points where they were checked, gmsh split the
// crossing lines and aborted on the transfinite strip. At these sizes it
// did; strips are now kept clear of each other on exact segments.
TEST(Anisotropy, StripsOfAWideningGranularShockNeverCross) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const std::string shock = std::string(SOURCE_DIR) + "/tests/data/wedge_M3_10_granular_shock.csv";
  constexpr double kCrashedHMin[] = {0.0007, 0.000474};
  constexpr double kStudyHMax = 0.01007;
  for (const double h_min : kCrashedHMin) {
    const std::string dir = meshgen_test::fresh_dir("aniso_crossing");
    meshgen::MeshRequest r = meshgen::request_from_shock_csv(shock);
    r.h_min = h_min;
    r.h_max = kStudyHMax;
    const meshgen::MeshResult m = meshgen::generate_mesh(s, r, dir);
    const nlohmann::json j = summary(dir);
    EXPECT_TRUE(m.check_mesh_ok) << h_min << ": " << j.value("check_mesh_failures", "");
    EXPECT_LT(m.max_non_orthogonality, kMaxNonOrthogonality) << h_min;
    EXPECT_GE(j["band_strips"].get<long>(), 2) << h_min;
  }
}

// The case study's clustered family as `pipeline run` meshes it (its band
// round the apex ray, recorded from a studies run): on coarse levels the
// strip's growth rows crossed the wedge or the domain's edge, no strip (or
// a short one) was laid, and the h 1.8 grid had more cells (2303) than the
// h 1.4 one (2251). Shorter strip cells are now tried where the full aspect
// covers too little: every level keeps a strip and the family's cells grow
// with its resolution.
TEST(Anisotropy, EveryLevelOfAWedgeFamilyKeepsAStripAndCellsGrowWithResolution) {
  const scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  const std::string ray = std::string(SOURCE_DIR) + "/tests/data/wedge_M3_10_shock_ray.csv";
  constexpr double kLevels[] = {10, 7, 5, 3.5, 2.5, 1.8, 1.4, 1};
  constexpr double kCaseHMin = 0.0047, kCaseHMax = 0.1;
  long previous = 0;
  for (const double level : kLevels) {
    const std::string dir = meshgen_test::fresh_dir("aniso_family");
    meshgen::MeshRequest r = meshgen::request_from_shock_csv(ray);
    r.h_min = kCaseHMin * level;
    r.h_max = kCaseHMax * level;
    const meshgen::MeshResult m = meshgen::generate_mesh(s, r, dir);
    const nlohmann::json j = summary(dir);
    EXPECT_TRUE(m.check_mesh_ok) << level;
    EXPECT_LT(m.max_non_orthogonality, kMaxNonOrthogonality) << level;
    EXPECT_GE(j["band_strips"].get<long>(), 1) << level;
    EXPECT_GT(m.cells, previous) << "level " << level;
    previous = m.cells;
  }
}

// Strips gmsh cannot mesh round (here two that cross: gmsh splits the
// crossing lines, then aborts on the transfinite surface from inside a
// thread where nothing can catch it) end the meshing child with gmsh's own
// message, a RunError the caller can act on, not "crashed (signal 6)".
TEST(Anisotropy, StripsGmshRejectsFailWithGmshsOwnMessage) {
  scene::Scene s = scene::load_scene(meshgen_test::case_path("wedge_M3_10"));
  s.domain_override = scene::Domain{-1.0, 4.0, 0.0, 4.0, true};
  const meshgen::FluidRegion region = meshgen::make_fluid_region(s);
  const auto strip = [](scene::Vec2 from, scene::Vec2 to) {
    meshgen::ShockStrip st;
    constexpr int kStations = 6;
    const scene::Vec2 along = scene::normalized(to - from);
    for (int i = 0; i < kStations; ++i) {
      st.centre.push_back(from + (static_cast<double>(i) / (kStations - 1)) * (to - from));
      st.normal.push_back(scene::perp(along));
    }
    st.rows = {-0.1, -0.05, 0.0, 0.05, 0.1};
    st.along.assign(kStations - 1, scene::norm(to - from) / (kStations - 1));
    return st;
  };
  const std::vector<meshgen::ShockStrip> crossing{strip({1.0, 2.0}, {3.0, 2.0}),
                                                  strip({2.0, 1.0}, {2.0, 3.0})};
  meshgen::GmshJob job;
  constexpr double kCell = 0.1;
  const std::string scratch = meshgen_test::fresh_dir("aniso_rejected") + "/plane_mesh.bin";
  try {
    meshgen::mesh_with_gmsh_in_child(
        region, [](scene::Vec2) { return kCell; }, crossing, job, scratch);
    FAIL() << "gmsh meshed round two crossing strips";
  } catch (const scene::RunError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("gmsh failed: ", 0), 0u) << e.what();
  }
}

TEST(Anisotropy, BadValuesAreRefusedNamingTheKey) {
  const std::string dir = meshgen_test::fresh_dir("aniso_refuse");
  const std::string shock = dir + "/shock.csv";
  meshgen_test::write_shock_csv(shock, {{0.0, 0.0}, {1.0, 0.5}}, 0.01);
  for (const char* v : {"0.5", "0", "-3", "51", ".nan", "ten"}) {
    SCOPED_TRACE(v);
    const std::string sub = dir + "/" + std::to_string(std::hash<std::string>{}(v));
    std::filesystem::create_directories(sub);
    const std::string scene = write_scene(
        sub,
        std::string("body: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n") +
            "mesh: {anisotropy: " + v + "}\n");
    expect_refusal(test_support::run_cli(test_support::stage_exe("meshgen"),
                                         scene + " --shock " + shock + " --out " + dir + "/out"),
                   "mesh.anisotropy");
    EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  }
}
