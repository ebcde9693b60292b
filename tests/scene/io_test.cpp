// Atomic writes: a failed write leaves the previous good file untouched.
#include "scene/io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scratch.hpp"

namespace fs = std::filesystem;

TEST(Io, FailedWriteKeepsThePreviousFile) {
  const fs::path d = test_support::scratch_root() / "scene_test_io";
  fs::remove_all(d);
  const auto path = (d / "summary.json").string();
  scene::write_json_atomic(path, {{"collisions", 42}});
  EXPECT_THROW(scene::write_stream_atomic(path, [](std::ostream& os) {
                 os << "half";
                 throw std::runtime_error("crash mid-write");
               }),
               std::runtime_error);
  EXPECT_EQ(nlohmann::json::parse(scene::read_file(path))["collisions"], 42);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++files;
  EXPECT_EQ(files, 1);  // no temporary left behind
}

TEST(Io, NonFiniteNumbersBecomeNull) {
  const fs::path d = test_support::scratch_root() / "scene_test_io2";
  const auto path = (d / "s.json").string();
  scene::write_json_atomic(path, {{"standoff", std::nan("")}, {"x", 1.5}});
  const auto j = nlohmann::json::parse(scene::read_file(path));
  EXPECT_TRUE(j["standoff"].is_null());
  EXPECT_DOUBLE_EQ(j["x"].get<double>(), 1.5);
}
