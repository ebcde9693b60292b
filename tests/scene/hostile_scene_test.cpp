// Scenes a hostile user writes: YAML structure that yaml-cpp accepts but a
// scene must not hold, and numbers at the edge of what a double carries.
// Each is an InputError naming the file, the key or line, and what is
// expected.
#include <gtest/gtest.h>

#include <string>

#include "scene/errors.hpp"
#include "scene/scene.hpp"

namespace {

void expect_error(const std::string& text, const std::string& needle) {
  try {
    scene::parse_scene(text, "bad.yaml");
    FAIL() << "no error for:\n" << text;
  } catch (const scene::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("bad.yaml", 0), 0u) << "message does not start with the file: " << msg;
    EXPECT_NE(msg.find(needle), std::string::npos)
        << "message: " << msg << "\nexpected to contain: " << needle;
  }
}

constexpr const char* kBody = "body: {kind: wedge, angle_deg: 10}\n";

}  // namespace

TEST(HostileScene, DuplicateKeyNamesTheKeyAndItsLine) {
  expect_error(std::string(kBody) + "freestream: {mach: 3}\nfreestream: {mach: 4}\n",
               "bad.yaml:3: key 'freestream': duplicate key");
  expect_error(std::string(kBody) + "freestream:\n  mach: 3\n  mach: 4\n",
               "bad.yaml:4: key 'freestream.mach': duplicate");
}

TEST(HostileScene, SecondDocumentIsRefused) {
  expect_error(std::string(kBody) + "freestream: {mach: 3}\n---\nfreestream: {mach: 4}\n",
               "expected one YAML document, found 2");
}

TEST(HostileScene, ComplexKeysAreInputErrors) {
  expect_error(std::string(kBody) + "freestream: {mach: 3}\n? [a, b]\n: 1\n",
               "expected plain scalar keys, got a list");
  expect_error(std::string(kBody) + "freestream: {mach: 3, {x: 1}: 2}\n", "got a mapping as a key");
}

TEST(HostileScene, DeepNestingIsRefusedNotRecursedInto) {
  expect_error(std::string(kBody) + "freestream: {mach: 3}\nx: " + std::string(200, '[') +
                   std::string(200, ']') + "\n",
               "nested deeper than");
}

TEST(HostileScene, ParticleCountOfTwoToThe63IsRefused) {
  expect_error("box: {width: 100, height: 100}\ngranular: {particles: 9223372036854775808}\n",
               "key 'granular.particles': expected an integer in [1, 9223372036854775807]");
  expect_error("box: {width: 100, height: 100}\ngranular: {particles: 1e300}\n",
               "key 'granular.particles'");
}

TEST(HostileScene, ExtremeNumbersAreRefusedWithTheRange) {
  expect_error(std::string(kBody) + "freestream: {mach: 1e308}\n",
               "key 'freestream.mach': expected a number in (0, 50]");
  expect_error(std::string(kBody) + "freestream: {mach: .inf}\n",
               "key 'freestream.mach': expected a number > 0");
  expect_error(std::string(kBody) + "freestream: {mach: .nan}\n", "key 'freestream.mach'");
  expect_error(std::string(kBody) + "freestream: {mach: 3}\ngranular: {mach: 1e308}\n",
               "key 'granular.mach': expected a number in (0, 50]");
  expect_error(std::string(kBody) + "freestream: {mach: 3}\ngranular: {gravity: [1e300, 0]}\n",
               "key 'granular.gravity'");
  expect_error(std::string(kBody) + "freestream: {mach: 3}\ngranular: {averaging: 1e300}\n",
               "key 'granular.averaging'");
  expect_error(
      std::string(kBody) + "freestream: {mach: 3}\ngranular: {checkpoint_interval: 1e300}\n",
      "key 'granular.checkpoint_interval'");
  expect_error(std::string(kBody) + "freestream: {mach: 3}\ncfd: {end_time: 1e300}\n",
               "key 'cfd.end_time'");
  expect_error(
      std::string(kBody) + "freestream: {mach: 3}\ncfd: {end_time: 10, write_interval: 1e-9}\n",
      "key 'cfd.write_interval'");
  expect_error("body: {kind: disc, radius: 1e300}\nfreestream: {mach: 3}\n",
               "key 'body.radius': expected a number in [1e-06, 1e+06]");
  expect_error("body: {kind: wedge, angle_deg: 10, length: 1e-300}\nfreestream: {mach: 3}\n",
               "key 'body.length'");
  expect_error(
      "body: {kind: polygon, points: [[0, 0], [1e300, 1], [1e300, -1]]}\nfreestream: {mach: 3}\n",
      "key 'body.points'");
  expect_error(std::string(kBody) +
                   "freestream: {mach: 3}\ndomain: {xmin: -1e300, xmax: 1, ymin: 0, ymax: 1, "
                   "symmetric: true}\n",
               "key 'domain.xmin'");
  expect_error("box: {width: 1e300, height: 100}\ngranular: {particles: 10}\n", "key 'box.width'");
}

TEST(HostileScene, SubsonicScenesParseButStagesCanRefuseThem) {
  const scene::Scene s =
      scene::parse_scene(std::string(kBody) + "freestream: {mach: 0.8}\n", "sub.yaml");
  try {
    scene::require_supersonic(s, "meshgen");
    FAIL() << "no error";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "sub.yaml: key 'freestream.mach': meshgen needs a supersonic free stream"),
              std::string::npos)
        << e.what();
  }
}
