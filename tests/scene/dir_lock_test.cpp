// Two runs into one output directory: the second is refused while the first
// holds the lock, and the lock is free again once the first ends.
#include "scene/dir_lock.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

#include "scene/errors.hpp"
#include "scratch.hpp"

TEST(DirLock, SecondRunIsRefusedUntilTheFirstEnds) {
  const auto dir = (test_support::scratch_root() / "shockgrain_dir_lock_test").string();
  std::filesystem::remove_all(dir);
  std::optional<scene::DirLock> first(std::in_place, dir);
  try {
    scene::DirLock second(dir);
    FAIL() << "a second lock on the same directory was granted";
  } catch (const scene::RunError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("another run is writing here"), std::string::npos) << msg;
    EXPECT_NE(msg.find(dir), std::string::npos) << msg;
  }
  first.reset();
  EXPECT_NO_THROW(scene::DirLock again(dir));
}
