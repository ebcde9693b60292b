// Template filling and run-time lookup; no OpenFOAM needed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "case_setup.hpp"
#include "cfd/run_case.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "test_util.hpp"

namespace {

TEST(Template, FillsEveryPlaceholder) {
  const std::string out = cfd::fill_placeholders("maxCo @MAX_CO@; U (@MACH@ 0 0); again @MACH@;",
                                                 {{"MAX_CO", "0.3"}, {"MACH", "5"}}, "t");
  EXPECT_EQ(out, "maxCo 0.3; U (5 0 0); again 5;");
}

TEST(Template, LeftoverPlaceholderNamesFileAndKey) {
  try {
    (void)cfd::fill_placeholders("endTime @END_TIME@;", {{"MACH", "5"}}, "system/controlDict");
    FAIL() << "expected an error";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "system/controlDict: placeholder @END_TIME@ has no value");
  }
}

TEST(Template, DirectoryHoldsTheOpenFoamLayout) {
  const std::filesystem::path d = cfd::template_dir();
  for (const char* f : {"rhoCentralFoam/0.orig/p", "rhoCentralFoam/0.orig/T", "rhoCentralFoam/0.orig/U",
                        "rhoCentralFoam/constant/thermophysicalProperties", "rhoCentralFoam/system/controlDict",
                        "rhoCentralFoam/system/fvSchemes", "rhoCentralFoam/system/fvSolution",
                        "rhoCentralFoam/system/decomposeParDict", "rhoCentralFoam/Allrun", "blockMesh/system/blockMeshDict"})
    EXPECT_TRUE(std::filesystem::exists(d / f)) << f;
}

TEST(RunCase, MissingMeshIsInputError) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0);
  const std::string dir = cfd_test::scratch_dir();
  try {
    (void)cfd::run_case(s, dir + "/nowhere", dir + "/case", {});
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + "/nowhere: no constant/polyMesh (run meshgen or cfd blockmesh first)");
  }
}

TEST(BlockMesh, DetachedWedgeIsInputError) {
  // theta = 40 deg exceeds the maximum deflection at Mach 3 (34.1 deg).
  const scene::Scene s = cfd_test::wedge_scene(3.0, 40.0);
  try {
    cfd::make_wedge_block_mesh(s, 1000, cfd_test::scratch_dir());
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<string>: the shock is detached at this Mach number; blockmesh covers attached wedges");
  }
}

TEST(Params, CfdSectionRejectsUnknownFluxScheme) {
  try {
    (void)cfd_test::wedge_scene(3.0, 10.0, "{flux_scheme: Roe}");
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cfd.flux_scheme"), std::string::npos) << e.what();
  }
}

TEST(Params, LocalTimeSteppingAutoIsTimeAccurateAndTrueOrFalseOverride) {
  // auto: time-accurate for every flow (LTS's steady stop left a larger
  // error on fine wedge grids); true and false are the user's choice.
  EXPECT_FALSE(cfd::local_time_stepping(cfd_test::wedge_scene(3.0, 10.0)));
  EXPECT_FALSE(cfd::local_time_stepping(cfd_test::wedge_scene(3.0, 10.0, "{local_time_stepping: auto}")));
  EXPECT_TRUE(cfd::local_time_stepping(cfd_test::wedge_scene(3.0, 10.0, "{local_time_stepping: true}")));
  EXPECT_FALSE(cfd::local_time_stepping(cfd_test::wedge_scene(3.0, 10.0, "{local_time_stepping: false}")));
  const scene::Scene disc =
      scene::parse_scene("name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
  EXPECT_FALSE(cfd::local_time_stepping(disc));
}

TEST(Params, LocalTimeSteppingRejectsOtherWords) {
  try {
    (void)cfd_test::wedge_scene(3.0, 10.0, "{local_time_stepping: sometimes}");
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cfd.local_time_stepping"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("auto"), std::string::npos) << e.what();
  }
}

TEST(FarField, CaseStudiesKeepTheSupersonicOutflowAndTheirStart) {
  // The shipped case studies: outflow supersonic (zeroGradient, as before),
  // blunt bodies started at rest, attached wedges in the free stream.
  for (const char* name : {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"}) {
    const scene::Scene s =
        scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    EXPECT_FALSE(cfd::subsonic_outflow(s)) << name;
    EXPECT_EQ(cfd::far_field_pressure(s), "type zeroGradient;") << name;
    EXPECT_EQ(cfd::start_at_rest(s), s.body->kind != scene::BodyKind::wedge) << name;
  }
}

TEST(FarField, NearSonicDiscHasASubsonicOutflowAndStartsInTheFreeStream) {
  // Mach 1.3: Billig's shock crosses the disc's widest station at ~72 deg,
  // with Mach ~0.9 behind it; the start at rest would send a shock out
  // through the inlet (below Mach 1.58).
  const scene::Scene s =
      scene::parse_scene("name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\n");
  EXPECT_LT(scene::post_shock_mach_at_outflow(s), 1.0);
  EXPECT_TRUE(cfd::subsonic_outflow(s));
  EXPECT_NE(cfd::far_field_pressure(s).find("type waveTransmissive;"), std::string::npos);
  EXPECT_NE(cfd::far_field_pressure(s).find("fieldInf 1;"), std::string::npos);
  EXPECT_NE(cfd::far_field_pressure(s).find("lInf 0.5;"), std::string::npos);  // one radius
  EXPECT_FALSE(cfd::start_at_rest(s));
  // cfd.start still overrides.
  EXPECT_TRUE(cfd::start_at_rest(scene::parse_scene(
      "name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\ncfd: {start: rest}\n")));
  // Just above the rest-start limit the disc starts at rest again.
  EXPECT_TRUE(cfd::start_at_rest(
      scene::parse_scene("name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.6}\n")));
}

TEST(FarField, AttachedWedgeNearMaximumDeflectionCanLeaveSubsonic) {
  // Mach 2, 22.9 deg (maximum deflection 22.97 deg): the weak shock leaves
  // Mach 0.963 behind it; at 22 deg, 1.076 (exact oblique-shock relations).
  constexpr double kMachTol = 1e-3;
  EXPECT_NEAR(scene::post_shock_mach_at_outflow(cfd_test::wedge_scene(2.0, 22.9)), 0.9629,
              kMachTol);
  EXPECT_NEAR(scene::post_shock_mach_at_outflow(cfd_test::wedge_scene(2.0, 22.0)), 1.0760,
              kMachTol);
  EXPECT_TRUE(cfd::subsonic_outflow(cfd_test::wedge_scene(2.0, 22.9)));
  EXPECT_FALSE(cfd::subsonic_outflow(cfd_test::wedge_scene(2.0, 10.0)));
}

TEST(FarField, DetachedWedgeLeavesSubsonicOnlyWhereTheDomainCutsItsShoulder) {
  // Mach 2, 30 deg: beyond the maximum deflection; the sonic line starts at
  // the wedge's base corner. The default domain runs one base height past
  // the base, so the flow turns supersonic round the corner before the
  // outflow (Billig's shock alone leaves Mach > 1 behind it there too).
  const scene::Scene s = cfd_test::wedge_scene(2.0, 30.0);
  const double base_x = std::cos(30.0 * scene::kDeg),
               base_height = 2.0 * std::sin(30.0 * scene::kDeg);
  constexpr double kRoundOff = 1e-12;  // the domain is built from the same cos and sin
  EXPECT_NEAR(scene::scene_domain(s).xmax, base_x + base_height, kRoundOff);
  EXPECT_GT(scene::post_shock_mach_at_outflow(s), 1.0);
  EXPECT_FALSE(cfd::subsonic_outflow(s));
  // A domain cut at the base corner: the flow leaves subsonic.
  const scene::Scene cut = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\ndomain: {xmin: -2.5, "
      "xmax: " +
      fmt::format("{:.17g}", base_x) + ", ymin: 0, ymax: 5, symmetric: true}\n");
  EXPECT_TRUE(cfd::subsonic_outflow(cut));
  EXPECT_FALSE(cfd::start_at_rest(s));  // wedges start in the free stream
}

TEST(FluxScheme, AutoIsTadmorWhereAFreeStreamStartMeetsASharpBaseOrARestStartIsHypersonic) {
  // The case studies keep what they were measured with: Kurganov (Apollo M5
  // names Tadmor, which auto now gives it too).
  for (const char* name : {"wedge_M3_10", "wedge_M4_15", "wedge_M5_20", "disc_M4", "apollo_M5"}) {
    const scene::Scene s =
        scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    EXPECT_EQ(cfd::flux_scheme(s), s.cfd.flux_scheme == "auto" ? "Kurganov" : s.cfd.flux_scheme)
        << name;
  }
  // Bodies started at rest: Kurganov up to Mach 4.5, Tadmor from there
  // (Kurganov diverged from the impulsive start at Mach 5-8), unless named.
  const auto at = [](const std::string& body, double mach, const std::string& cfd = "") {
    return scene::parse_scene("name: t\nbody: " + body +
                              "\nfreestream: {mach: " + std::to_string(mach) + "}\n" + cfd);
  };
  const std::string disc_body = "{kind: disc, radius: 0.5}",
                    apollo_body = "{kind: apollo, diameter: 1.0}";
  const std::string notched_body =
      "{kind: polygon, points: [[0, -0.5], [1, -0.5], [0.7, 0], [1, 0.5], [0, 0.5]]}";
  for (const std::string& body : {disc_body, apollo_body, notched_body}) {
    SCOPED_TRACE(body);
    EXPECT_TRUE(cfd::start_at_rest(at(body, 4.0)));
    EXPECT_EQ(cfd::flux_scheme(at(body, 4.0)), "Kurganov");
    EXPECT_EQ(cfd::flux_scheme(at(body, 4.49)), "Kurganov");
    EXPECT_EQ(cfd::flux_scheme(at(body, 4.5)), "Tadmor");
    EXPECT_EQ(cfd::flux_scheme(at(body, 8.0)), "Tadmor");
    EXPECT_EQ(cfd::flux_scheme(at(body, 8.0, "cfd: {flux_scheme: Kurganov}\n")), "Kurganov");
    EXPECT_EQ(cfd::flux_scheme(at(body, 8.0, "cfd: {start: freestream}\n")), "Kurganov");
  }
  // A detached wedge: its base and wake lie inside the default domain and it
  // starts in the free stream.
  const scene::Scene detached = cfd_test::wedge_scene(2.0, 30.0);
  EXPECT_TRUE(scene::sharp_base_inside_domain(detached));
  EXPECT_EQ(cfd::flux_scheme(detached), "Tadmor");
  // An attached wedge is cut at its base: no base inside.
  EXPECT_FALSE(scene::sharp_base_inside_domain(cfd_test::wedge_scene(3.0, 10.0)));
  EXPECT_EQ(cfd::flux_scheme(cfd_test::wedge_scene(3.0, 10.0)), "Kurganov");
  // Started at rest, or with the flux named, the detached wedge keeps what it is given.
  const std::string m2_30 = "name: w\nbody: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n";
  EXPECT_EQ(cfd::flux_scheme(scene::parse_scene(m2_30 + "cfd: {start: rest}\n")), "Kurganov");
  EXPECT_EQ(cfd::flux_scheme(scene::parse_scene(m2_30 + "cfd: {flux_scheme: Kurganov}\n")),
            "Kurganov");
  // A near-sonic disc starts in the free stream but has no sharp base.
  const scene::Scene disc =
      scene::parse_scene("name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\n");
  EXPECT_FALSE(cfd::start_at_rest(disc));
  EXPECT_EQ(cfd::flux_scheme(disc), "Kurganov");
}

TEST(FarField, PointedPolygonKeepsTheSupersonicOutflow) {
  // An arrow at Mach 3: its 22 deg nose carries an attached shock and the
  // flow reaches the barbs on the outflow boundary supersonic.
  const scene::Scene s = scene::parse_scene(
      "name: arrow\nbody: {kind: polygon, points: [[0, 0], [1, 0.4], [0.7, 0], [1, -0.4]]}\nfreestream: {mach: 3}\n");
  EXPECT_FALSE(cfd::subsonic_outflow(s));
  EXPECT_TRUE(cfd::start_at_rest(s));
}

}  // namespace

TEST(InitialState, ADetachedWedgeStartsWithItsWakeAtRest) {
  const scene::Scene detached = cfd_test::wedge_scene(3.0, 36.0);
  EXPECT_EQ(cfd::initial_state(detached), "rest_behind_base");
  EXPECT_FALSE(cfd::start_at_rest(detached));
  EXPECT_EQ(cfd::flux_scheme(detached), "Tadmor");
  EXPECT_EQ(cfd::initial_state(cfd_test::wedge_scene(3.0, 10.0)), "freestream");
  // Below the rest-start limit (1.58 for air) a detached wedge starts in the
  // free stream: the shock facing upstream from the gas at rest would run out
  // through the inlet.
  const scene::Scene near_sonic = cfd_test::wedge_scene(1.5, 20.0);
  EXPECT_TRUE(scene::sharp_base_inside_domain(near_sonic));
  EXPECT_EQ(cfd::initial_state(near_sonic), "freestream");
  EXPECT_EQ(cfd::initial_state(cfd_test::wedge_scene(1.6, 20.0)), "rest_behind_base");
  EXPECT_EQ(cfd::initial_state(scene::parse_scene(
                "name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n")),
            "rest");
  // Named starts win; rest_behind_base needs a base inside the domain.
  const std::string m3_36 = "name: w\nbody: {kind: wedge, angle_deg: 36}\nfreestream: {mach: 3}\n";
  EXPECT_EQ(cfd::initial_state(scene::parse_scene(m3_36 + "cfd: {start: freestream}\n")),
            "freestream");
  EXPECT_EQ(cfd::initial_state(scene::parse_scene(m3_36 + "cfd: {start: rest}\n")), "rest");
  EXPECT_THROW((void)cfd::initial_state(scene::parse_scene(
                   "name: w\nbody: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n"
                   "cfd: {start: rest_behind_base}\n")),
               scene::InputError);
  EXPECT_THROW((void)scene::parse_scene(m3_36 + "cfd: {start: wake}\n"), scene::InputError);
}

TEST(InitialState, TheVelocityIsTheFreeStreamAheadOfTheBaseAndZeroBehindIt) {
  // Three cells: ahead of the apex, over the wedge, behind its base.
  const scene::Scene s = cfd_test::wedge_scene(3.0, 36.0);
  const double x_base = scene::widest_station_x(s);
  EXPECT_NEAR(x_base, std::cos(36.0 * scene::kDeg), 1e-12);
  cfd::Mesh2D mesh;
  for (const double x : {-0.5, 0.5 * x_base, x_base + 0.1}) {
    mesh.cell_centre.push_back({x, 1.0});
    mesh.cell_area.push_back(1.0);
  }
  EXPECT_EQ(cfd::initial_velocity_field(s, mesh),
            "nonuniform List<vector> 3\n(\n(3 0 0)\n(3 0 0)\n(0 0 0)\n)");
  EXPECT_EQ(cfd::initial_velocity_field(cfd_test::wedge_scene(3.0, 10.0), mesh), "uniform (3 0 0)");
}

TEST(InitialState, TheOutletLetsNoGasInBehindASharpBase) {
  EXPECT_EQ(cfd::outlet_velocity(cfd_test::wedge_scene(3.0, 36.0)),
            "type inletOutlet; inletValue uniform (0 0 0);");
  EXPECT_EQ(cfd::outlet_velocity(cfd_test::wedge_scene(3.0, 10.0)), "type zeroGradient;");
  EXPECT_EQ(cfd::outlet_velocity(scene::parse_scene(
                "name: t\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n")),
            "type zeroGradient;");
}
