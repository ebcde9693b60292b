#pragma once
// Helpers shared by the cfd tests: scenes as text, scratch directories.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "scene/scene.hpp"
#include "scratch.hpp"

namespace cfd_test {

inline scene::Scene wedge_scene(double mach, double angle_deg, const std::string& cfd_section = "{}") {
  return scene::parse_scene("name: test_wedge\nbody: {kind: wedge, angle_deg: " + std::to_string(angle_deg) +
                            ", length: 1.0}\nfreestream: {mach: " + std::to_string(mach) +
                            "}\ncfd: " + cfd_section + "\n");
}

// A fresh directory under the build tree's test scratch area, named for the test.
inline std::string scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return test_support::fresh_dir("cfd/" + std::string(info->test_suite_name()) + "." +
                                 info->name());
}

}  // namespace cfd_test
