// Stage cache: fingerprints and records.
#include <gtest/gtest.h>

#include <filesystem>

#include "pipeline/stage_cache.hpp"
#include "scratch.hpp"

TEST(Cache, FingerprintSeparatesParts) {
  EXPECT_NE(pipeline::fingerprint({"ab", "c"}), pipeline::fingerprint({"a", "bc"}));
  EXPECT_EQ(pipeline::fingerprint({"x"}), pipeline::fingerprint({"x"}));
  EXPECT_EQ(pipeline::fingerprint({"x"}).size(), 16u);
}

TEST(Cache, RecordMakesAStageFreshUntilInvalidated) {
  const auto root = (test_support::scratch_root() / "pipeline_cache_test").string();
  std::filesystem::remove_all(root);
  pipeline::StageCache c(root);
  EXPECT_FALSE(c.fresh("granular", "abc"));
  c.mark_done("granular", "abc", {{"wall_seconds", 3.5}});
  EXPECT_TRUE(c.fresh("granular", "abc"));
  EXPECT_FALSE(c.fresh("granular", "abd"));  // a changed parameter reruns
  EXPECT_DOUBLE_EQ(c.result("granular")["wall_seconds"].get<double>(), 3.5);
  c.invalidate("granular");
  EXPECT_FALSE(c.fresh("granular", "abc"));
}
