// Calibration table: round trip and interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/calibration.hpp"
#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"

TEST(Calibration, RoundTripAndInterpolation) {
  pipeline::CalibrationTable t;
  t.entries = {{3, 10, 0.8, 0.02, 27.38, 27.5, 0.3}, {5, 20, 0.6, 0.03, 29.8, 29.9, 0.4}};
  const auto path = (std::filesystem::temp_directory_path() / "calib_test.yaml").string();
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_EQ(back.entries.size(), 2u);
  EXPECT_DOUBLE_EQ(back.entries[1].restitution, 0.6);
  EXPECT_DOUBLE_EQ(*pipeline::interpolate_restitution(back, 3, 10), 0.8);  // exact match
  const double mid = *pipeline::interpolate_restitution(back, 4, 15);       // equidistant
  EXPECT_NEAR(mid, 0.7, 1e-12);
  EXPECT_FALSE(pipeline::interpolate_restitution(pipeline::CalibrationTable{}, 3, 10).has_value());
  // Blunt bodies (no angle): by Mach alone, M = 3 matches the first entry.
  EXPECT_DOUBLE_EQ(*pipeline::interpolate_restitution(back, 3, NAN), 0.8);
}

TEST(Calibration, AppliedOnlyWhenTheSceneLeavesRestitutionUnset) {
  pipeline::CalibrationTable t;
  t.entries = {{3, 10, 0.8, 0.02, 27.38, 27.5, 0.3}};
  const auto path = (std::filesystem::temp_directory_path() / "calib_apply.yaml").string();
  pipeline::write_calibration(t, path);
  auto s = scene::parse_scene("body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  EXPECT_NE(pipeline::apply_calibration(s, path).find("from the calibration table"), std::string::npos);
  EXPECT_DOUBLE_EQ(s.granular.restitution, 0.8);
  auto given = scene::parse_scene("body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\ngranular: {restitution: 0.95}\n");
  EXPECT_EQ(pipeline::apply_calibration(given, path), "");
  EXPECT_DOUBLE_EQ(given.granular.restitution, 0.95);
}

TEST(Calibration, MalformedTableIsInputError) {
  const auto path = (std::filesystem::temp_directory_path() / "calib_bad.yaml").string();
  scene::write_file_atomic(path, "entries: [{mach: 3, angle_deg: 10, restitution: 1.7}]\n");
  EXPECT_THROW(pipeline::read_calibration(path), scene::InputError);
  EXPECT_THROW(pipeline::read_calibration("/nonexistent/calib.yaml"), scene::InputError);
}
