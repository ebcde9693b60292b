// Scene parsing: defaults, every error path with its message, and the
// shipped case studies.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"

using scene::InputError;
using scene::parse_scene;

namespace {

// Expects parse_scene(text) to throw InputError whose message contains `needle`.
void expect_error(const std::string& text, const std::string& needle) {
  try {
    parse_scene(text, "bad.yaml");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << needle;
  }
}

constexpr const char* kMinimal = "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n";

}  // namespace

TEST(Parse, MinimalSceneTakesDefaults) {
  const auto s = parse_scene(kMinimal, "dir/wedge.yaml");
  EXPECT_EQ(s.name, "wedge");  // file stem
  ASSERT_TRUE(s.body.has_value());
  EXPECT_EQ(s.body->kind, scene::BodyKind::wedge);
  EXPECT_DOUBLE_EQ(s.body->length, 1.0);
  EXPECT_DOUBLE_EQ(s.freestream.gamma, 1.4);
  EXPECT_DOUBLE_EQ(s.granular.restitution, 1.0);
  EXPECT_EQ(s.granular.lattice_nx, 200);
  EXPECT_FALSE(s.box.has_value());
}

TEST(Parse, BandAnisotropyDefaultsToStripsOnlyOnAnAttachedShock) {
  // Attached oblique shock (M3, 10 deg): straight, strips by default.
  EXPECT_DOUBLE_EQ(scene::band_anisotropy(parse_scene(kMinimal, "w.yaml")),
                   scene::kStraightShockAnisotropy);
  // Beyond the maximum deflection (M2, 30 deg) the shock stands off: isotropic.
  EXPECT_DOUBLE_EQ(scene::band_anisotropy(parse_scene(
                       "body: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n", "d.yaml")),
                   1.0);
  EXPECT_DOUBLE_EQ(scene::band_anisotropy(parse_scene(
                       "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n", "c.yaml")),
                   1.0);
  // The scene's own value wins either way.
  EXPECT_DOUBLE_EQ(scene::band_anisotropy(
                       parse_scene(std::string(kMinimal) + "mesh: {anisotropy: 1}\n", "w1.yaml")),
                   1.0);
  EXPECT_DOUBLE_EQ(
      scene::band_anisotropy(parse_scene(
          "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\nmesh: {anisotropy: 4}\n",
          "c4.yaml")),
      4.0);
}

// An attached shock's angle averages kAttachedShockAveraging flow-through
// times unless the scene says otherwise; bow shocks and boxes keep 4.
TEST(Parse, AveragingDefaultsToLongerOnlyOnAnAttachedShock) {
  EXPECT_DOUBLE_EQ(parse_scene(kMinimal, "w.yaml").granular.averaging,
                   scene::kAttachedShockAveraging);
  EXPECT_DOUBLE_EQ(
      parse_scene("body: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n", "d.yaml")
          .granular.averaging,
      4.0);
  EXPECT_DOUBLE_EQ(parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n", "c.yaml")
                       .granular.averaging,
                   4.0);
  EXPECT_DOUBLE_EQ(parse_scene(std::string(kMinimal) + "granular: {averaging: 4}\n", "w4.yaml")
                       .granular.averaging,
                   4.0);
  // The resolved scene says what ran.
  const auto again = parse_scene(scene::to_yaml(parse_scene(kMinimal, "w.yaml")), "echo.yaml");
  EXPECT_DOUBLE_EQ(again.granular.averaging, scene::kAttachedShockAveraging);
}

// A bow shock (the gas shock detached) averages kBowShockReplicas replicas
// unless the scene says otherwise; attached shocks keep kDefaultReplicas.
TEST(Parse, ReplicasDefaultToMoreOnlyOnABowShock) {
  EXPECT_EQ(parse_scene(kMinimal, "w.yaml").granular.replicas, scene::kDefaultReplicas);
  const char* disc = "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n";
  EXPECT_EQ(parse_scene(disc, "c.yaml").granular.replicas, scene::kBowShockReplicas);
  EXPECT_EQ(parse_scene("body: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n", "d.yaml")
                .granular.replicas,
            scene::kBowShockReplicas);
  EXPECT_EQ(
      parse_scene(std::string(disc) + "granular: {replicas: 1}\n", "c1.yaml").granular.replicas, 1);
  const auto again = parse_scene(scene::to_yaml(parse_scene(disc, "c.yaml")), "echo.yaml");
  EXPECT_EQ(again.granular.replicas, scene::kBowShockReplicas);
}

TEST(Parse, ResolvedYamlRoundTrips) {
  const auto s = parse_scene(kMinimal, "w.yaml");
  const auto again = parse_scene(scene::to_yaml(s), "echo.yaml");
  EXPECT_EQ(scene::to_yaml(again), scene::to_yaml(s));
}

// The resolved scene reproduces the run: a computed value (a blunt body's
// domain edge, here -1.5336583142524611) reads back as the same double, so
// meshgen on scene.resolved.yaml makes the grid the pipeline made; a value
// written by hand stays as written.
TEST(Parse, ResolvedYamlKeepsComputedValuesBitForBit) {
  const auto s =
      parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4, gamma: 1.4}\n", "d.yaml");
  const std::string yaml = scene::to_yaml(s);
  const auto again = parse_scene(yaml, "echo.yaml");
  const scene::Domain a = scene::scene_domain(s), b = scene::scene_domain(again);
  EXPECT_EQ(a.xmin, b.xmin);
  EXPECT_EQ(a.xmax, b.xmax);
  EXPECT_EQ(a.ymin, b.ymin);
  EXPECT_EQ(a.ymax, b.ymax);
  EXPECT_NE(yaml.find("gamma: 1.4\n"), std::string::npos) << yaml;
}

TEST(Parse, UnknownKeyNamesKeyFileAndLine) {
  expect_error("body: {kind: wedge}\nfreestream: {mach: 3}\nbogus: 1\n", "bad.yaml:3: key 'bogus': unknown key");
  expect_error("body:\n  kind: wedge\n  angel_deg: 10\nfreestream: {mach: 3}\n", "bad.yaml:3: key 'body.angel_deg': unknown key");
  expect_error(std::string(kMinimal) + "granular:\n  restitutio: 0.9\n", "key 'granular.restitutio': unknown key");
}

TEST(Parse, MalformedYaml) { expect_error("body: {kind: wedge\nfreestream: [", "malformed YAML"); }

TEST(Parse, WrongTypes) {
  expect_error("body: {kind: wedge}\nfreestream: {mach: fast}\n", "key 'freestream.mach': expected a number > 0, got 'fast'");
  expect_error(std::string(kMinimal) + "granular: {seed: 1.5}\n", "key 'granular.seed': expected an integer");
  expect_error(std::string(kMinimal) + "granular: [1, 2]\n", "key 'granular': expected a mapping, got a list");
  expect_error(std::string(kMinimal) + "granular: {snapshots: maybe}\n", "expected true or false");
}

TEST(Parse, OutOfRangeValues) {
  expect_error("body: {kind: wedge}\nfreestream: {mach: 0}\n", "key 'freestream.mach': expected a number > 0, got 0");
  expect_error("body: {kind: wedge}\nfreestream: {mach: -2}\n", "expected a number > 0, got -2");
  expect_error(std::string(kMinimal) + "granular: {restitution: 1.5}\n", "key 'granular.restitution': expected a number in (0, 1], got 1.5");
  expect_error(std::string(kMinimal) + "granular: {restitution: 0}\n", "expected a number in (0, 1], got 0");
  expect_error(std::string(kMinimal) + "granular: {elastic_impact_speed: -1}\n",
               "key 'granular.elastic_impact_speed'");
  expect_error(std::string(kMinimal) + "granular: {elastic_impact_speed: 1e9}\n",
               "key 'granular.elastic_impact_speed'");
  expect_error("body: {kind: disc, radius: -1}\nfreestream: {mach: 3}\n",
               "key 'body.radius': expected a number in [1e-06, 1e+06], got -1");
  expect_error("body: {kind: wedge}\nfreestream: {mach: 3, gamma: 0.9}\n", "key 'freestream.gamma'");
  expect_error(std::string(kMinimal) + "mesh: {h_min: 0.1, h_max: 0.01}\n", "key 'mesh.h_min': must not exceed h_max");
}

TEST(Parse, RequiredPieces) {
  expect_error("freestream: {mach: 3}\n", "key 'body': required");
  expect_error("body: {kind: wedge}\n", "required: freestream.mach");
  expect_error("body: {angle_deg: 3}\nfreestream: {mach: 3}\n", "key 'body.kind': required");
  expect_error("body: {kind: cone}\nfreestream: {mach: 3}\n", "expected one of wedge | disc | apollo | polygon, got 'cone'");
  expect_error("- 1\n- 2\n", "expected a YAML mapping at the top level");
  expect_error(std::string(kMinimal) + "box: {width: 10}\n", "either a body or a box");
  expect_error(std::string(kMinimal) + "schema: 7\n", "this build reads schema 1, got 7");
}

TEST(Parse, BoxSceneResolvesParticlesFromPackingFraction) {
  const auto s = parse_scene("box: {width: 100, height: 100, periodic: true}\ngranular: {packing_fraction: 0.3}\n");
  ASSERT_TRUE(s.box.has_value());
  EXPECT_EQ(*s.granular.particles, 3820);  // contract's example: 0.30 -> 3820
  const auto t = parse_scene("box: {width: 100, height: 100}\ngranular: {particles: 3820}\n");
  EXPECT_NEAR(*t.granular.packing_fraction, 0.3, 0.0005);
}

TEST(Parse, BoxSceneParticlesAndFractionMustAgree) {
  // 3820 disks agree with 0.30 within 0.5%; 4000 do not (0.314).
  EXPECT_NO_THROW(parse_scene("box: {width: 100, height: 100}\ngranular: {particles: 3820, packing_fraction: 0.3}\n"));
  expect_error("box: {width: 100, height: 100}\ngranular: {particles: 4000, packing_fraction: 0.3}\n",
               "disagrees with packing_fraction");
  expect_error("box: {width: 100, height: 100}\ngranular: {restitution: 1}\n", "needs particles or packing_fraction");
}

TEST(Parse, PolygonErrorsNameTheProblem) {
  expect_error("body: {kind: polygon, points: [[0,0],[2,2],[2,0],[0,1]]}\nfreestream: {mach: 3}\n",
               "self-intersecting: edge 0");
  expect_error("body: {kind: polygon, points: [[0,0],[1,0]]}\nfreestream: {mach: 3}\n", "at least 3 distinct points");
  expect_error("body: {kind: polygon, points: [[0,0],[1,0],[1,0],[0,1]]}\nfreestream: {mach: 3}\n", "zero-length edge 1");
  expect_error("body: {kind: polygon, points: [[0,0],[1,0],[2,0]]}\nfreestream: {mach: 3}\n", "zero area");
  expect_error("body: {kind: polygon, points: [[0,0],[1]]}\nfreestream: {mach: 3}\n", "point 1: expected [x, y]");
  expect_error("body: {kind: polygon}\nfreestream: {mach: 3}\n", "key 'body.points': required");
}

// Every body kind takes the same size range, named by its own key: a disc
// too small to be a polygon must not fail later as an unnamed "zero area".
TEST(Parse, BodySizesShareOneRange) {
  expect_error("body: {kind: disc, radius: 1e-9}\nfreestream: {mach: 3}\n",
               "key 'body.radius': expected a number in [1e-06, 1e+06], got 1e-9");
  expect_error("body: {kind: apollo, diameter: 2e6}\nfreestream: {mach: 3}\n",
               "key 'body.diameter': expected a number in [1e-06, 1e+06], got 2e6");
  expect_error("body: {kind: wedge, length: 1e-7}\nfreestream: {mach: 3}\n", "key 'body.length'");
  for (const char* body : {"{kind: disc, radius: 1e-6}", "{kind: apollo, diameter: 1e-6}",
                           "{kind: wedge, angle_deg: 10, length: 1e-6}"}) {
    const auto s =
        parse_scene(std::string("body: ") + body + "\nfreestream: {mach: 3}\n", "tiny.yaml");
    EXPECT_NO_THROW((void)scene::make_body(*s.body)) << body;
  }
}

// Zero length and zero area are relative to the polygon's own size: a body
// given in metres at the scale of millimetres is a body, not a point.
TEST(Parse, TinyPolygonIsABody) {
  EXPECT_NO_THROW(
      parse_scene("body: {kind: polygon, points: "
                  "[[0,0],[1e-5,1e-6],[2e-5,0],[1e-5,-1e-6]]}\nfreestream: {mach: 3}\n",
                  "p.yaml"));
  expect_error("body: {kind: polygon, points: [[0,0],[1e-5,0],[2e-5,0]]}\nfreestream: {mach: 3}\n",
               "zero area");
}

TEST(Parse, DomainOverrideMustClearTheBody) {
  expect_error(std::string(kMinimal) + "domain: {xmin: 0.0, xmax: 1, ymin: 0, ymax: 1, symmetric: true}\n",
               "touches or crosses the inflow boundary");
  expect_error(std::string(kMinimal) + "domain: {xmin: -1, xmax: 1, ymin: 0, ymax: 0.1, symmetric: true}\n",
               "touches or crosses the side boundary y = ymax");
  expect_error(std::string(kMinimal) + "domain: {xmin: -1, xmax: 1, ymin: 0.5, ymax: 0.1}\n", "must exceed ymin");
  EXPECT_NO_THROW(parse_scene(std::string(kMinimal) + "domain: {xmin: -1, xmax: 0.9, ymin: 0, ymax: 1, symmetric: true}\n"));
}

TEST(Parse, MissingFileIsInputError) {
  EXPECT_THROW(scene::load_scene("/nonexistent/scene.yaml"), InputError);
}

TEST(Parse, EveryShippedSceneParses) {
  int count = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(SOURCE_DIR)) {
    const auto p = e.path();
    // Shipped means in the source tree, not in build folders or run outputs.
    const std::string top = std::filesystem::relative(p, SOURCE_DIR).begin()->string();
    if (p.extension() != ".yaml" || top.rfind("build", 0) == 0 || top == "out" || top == ".git") continue;
    if (p.filename() == "calibration.yaml") continue;  // a data table, not a scene
    if (p.string().find("/tests/data/bad") != std::string::npos) continue;  // deliberately broken inputs
    SCOPED_TRACE(p.string());
    EXPECT_NO_THROW(scene::load_scene(p.string()));
    ++count;
  }
  EXPECT_GE(count, 5);  // at least the five case studies
}

TEST(Parse, ABowShockGetsTheTimeItsStandoffNeedsToSettle) {
  // Where the shock may stand off, the steady rule waits for the standoff to
  // hold still (cfd_cases/src/steady_state.hpp), which reference grids reach
  // past the attached default of 10 flow-throughs.
  const auto end_time = [](const std::string& body_and_mach) {
    return scene::parse_scene("name: s\n" + body_and_mach).cfd.end_time;
  };
  EXPECT_EQ(end_time("body: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n"),
            10.0);
  EXPECT_EQ(end_time("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n"), 30.0);
  EXPECT_EQ(end_time("body: {kind: apollo, diameter: 1}\nfreestream: {mach: 5}\n"), 30.0);
  // Beyond its maximum deflection (23 deg at Mach 2) a wedge's shock stands off.
  EXPECT_EQ(end_time("body: {kind: wedge, angle_deg: 30, length: 1}\nfreestream: {mach: 2}\n"),
            30.0);
  // A scene that states its end_time keeps it.
  EXPECT_EQ(
      end_time("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\ncfd: {end_time: 12}\n"),
      12.0);
}
