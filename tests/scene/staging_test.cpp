// StagedDir: results swap in whole on success; a failure (destructor
// without commit) leaves the previous results and no staging folder.
#include "scene/staging.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/errors.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

std::string fresh(const std::string& name) {
  return test_support::fresh_dir("shockgrain_staging_" + name);
}

void put(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}
std::string get(const std::string& path) {
  std::ifstream is(path);
  return std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
}
int entries(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.exists() ? 1 : 0;
  return n;
}

}  // namespace

TEST(Staging, CommitReplacesAndKeepsOrDiscardsLeftovers) {
  const std::string root = fresh("commit");
  const std::string out = root + "/out";
  fs::create_directories(out);
  put(out + "/result", "old");
  put(out + "/other", "unrelated");
  {
    scene::StagedDir s(out);
    put(s.path() + "/result", "new");
    s.commit(scene::Leftovers::keep);
  }
  EXPECT_EQ(get(out + "/result"), "new");
  EXPECT_EQ(get(out + "/other"), "unrelated");
  {
    scene::StagedDir s(out);
    put(s.path() + "/result", "newer");
    s.commit(scene::Leftovers::discard);
  }
  EXPECT_EQ(get(out + "/result"), "newer");
  EXPECT_FALSE(fs::exists(out + "/other"));
  EXPECT_EQ(entries(root), 1);  // no staging or old folder left
}

TEST(Staging, AbandonedStagingLeavesThePreviousResults) {
  const std::string root = fresh("abandon");
  const std::string out = root + "/out";
  fs::create_directories(out);
  put(out + "/result", "good");
  try {
    scene::StagedDir s(out);
    put(s.path() + "/result", "half");
    throw scene::RunError("failed");
  } catch (const scene::RunError&) {
  }
  EXPECT_EQ(get(out + "/result"), "good");
  EXPECT_EQ(entries(root), 1);
}

TEST(Staging, KeepAsPutsTheRunBesideOut) {
  const std::string root = fresh("keep");
  const std::string out = root + "/out";
  fs::create_directories(out);
  put(out + "/result", "good");
  std::string kept;
  {
    scene::StagedDir s(out);
    put(s.path() + "/result", "partial");
    kept = s.keep_as(".partial");
  }
  EXPECT_EQ(kept, fs::weakly_canonical(out).string() + ".partial");
  EXPECT_EQ(get(out + "/result"), "good");
  EXPECT_EQ(get(kept + "/result"), "partial");
}

TEST(Staging, OutOverlappingAnInputIsRefused) {
  const std::string root = fresh("overlap");
  fs::create_directories(root + "/mesh/constant");
  EXPECT_THROW(scene::refuse_out_overlap(root + "/mesh", root + "/mesh", "--mesh folder"),
               scene::InputError);
  EXPECT_THROW(scene::refuse_out_overlap(root + "/mesh/", root + "/mesh", "--mesh folder"),
               scene::InputError);
  EXPECT_THROW(scene::refuse_out_overlap(root + "/mesh/case", root + "/mesh", "--mesh folder"),
               scene::InputError);
  EXPECT_THROW(scene::refuse_out_overlap(root, root + "/mesh", "--mesh folder"), scene::InputError);
  EXPECT_NO_THROW(scene::refuse_out_overlap(root + "/case", root + "/mesh", "--mesh folder"));
  EXPECT_NO_THROW(scene::refuse_out_overlap(root + "/mesh2", root + "/mesh", "--mesh folder"));
  try {
    scene::refuse_out_overlap(root + "/mesh", root + "/mesh", "--mesh folder");
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--mesh folder " + root + "/mesh"), std::string::npos)
        << e.what();
  }
  put(root + "/file", "x");
  EXPECT_THROW(scene::StagedDir(root + "/file"), scene::InputError);
}
