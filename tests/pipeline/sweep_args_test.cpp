// Sweep arguments and scene edits.
#include <gtest/gtest.h>

#include <filesystem>

#include "pipeline/studies.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

TEST(Sweep, ParseVary) {
  const auto v = pipeline::parse_vary("granular.restitution=0.8,0.9,1.0");
  EXPECT_EQ(v.key, "granular.restitution");
  ASSERT_EQ(v.values.size(), 3u);
  EXPECT_EQ(v.values[2], "1.0");
  EXPECT_THROW(pipeline::parse_vary("granular.restitution"), scene::InputError);
  EXPECT_THROW(pipeline::parse_vary("=1,2"), scene::InputError);
}

TEST(Sweep, SceneWithSetsNestedKeysAndRevalidates) {
  const auto path = (test_support::scratch_root() / "sweep_scene.yaml").string();
  scene::write_file_atomic(path, "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const auto s = pipeline::scene_with(path, {{"granular.restitution", "0.85"}, {"body.angle_deg", "15"}});
  EXPECT_DOUBLE_EQ(s.granular.restitution, 0.85);
  EXPECT_DOUBLE_EQ(s.body->angle_deg, 15.0);
  EXPECT_EQ(s.name, "sweep_scene");
  EXPECT_THROW(pipeline::scene_with(path, {{"granular.restitution", "1.5"}}), scene::InputError);
  EXPECT_THROW(pipeline::scene_with(path, {{"granular.no_such_key", "1"}}), scene::InputError);
}
