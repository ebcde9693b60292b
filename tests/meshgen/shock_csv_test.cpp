// shock.csv reading: columns by name, accepted rows in order, clear errors.
#include <gtest/gtest.h>

#include <fstream>

#include "meshgen/mesh.hpp"
#include "scene/errors.hpp"
#include "shock_fixtures.hpp"

namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = meshgen_test::fresh_dir("csv_" + name) + "/shock.csv";
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    (void)meshgen::request_from_shock_csv(path);
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ShockCsv, ReadsAcceptedRowsByNameInFileOrder) {
  const auto r = meshgen::request_from_shock_csv(
      write("ok", "accepted,ci,shock_y,station,shock_x\n1,0.01,0.1,0,-0.5\n0,0.5,9,1,9\n1,0.02,0.3,2,-0.4\n"));
  ASSERT_EQ(r.shock_curve.size(), 2u);
  EXPECT_DOUBLE_EQ(r.shock_curve[0].x, -0.5);
  EXPECT_DOUBLE_EQ(r.shock_curve[1].y, 0.3);
  ASSERT_EQ(r.shock_ci.size(), 2u);
  EXPECT_DOUBLE_EQ(r.shock_ci[1], 0.02);
  EXPECT_FALSE(r.uniform);
}

TEST(ShockCsv, CiColumnIsOptional) {
  const auto r = meshgen::request_from_shock_csv(write("noci", "shock_x,shock_y,accepted\n0,0,1\n1,1,1\n"));
  EXPECT_EQ(r.shock_curve.size(), 2u);
  EXPECT_TRUE(r.shock_ci.empty());
}

TEST(ShockCsv, ErrorsNameTheFileAndTheProblem) {
  const std::string missing = meshgen_test::fresh_dir("csv_missing") + "/nope.csv";
  EXPECT_EQ(error_of(missing), missing + ": shock file not found");
  const std::string empty = write("empty", "");
  EXPECT_EQ(error_of(empty), empty + ": shock file is empty (expected a header row with shock_x, shock_y, accepted)");
  const std::string header = write("header", "shock_x,shock_y,accepted\n");
  EXPECT_EQ(error_of(header), header + ": shock file has a header but no rows");
  const std::string nocol = write("nocol", "shock_x,shock_y\n0,0\n");
  EXPECT_EQ(error_of(nocol), nocol + ":1: missing column 'accepted'");
  const std::string none = write("none", "shock_x,shock_y,accepted\n0,0,0\n1,1,0\n");
  EXPECT_EQ(error_of(none), none + ": no accepted rows (accepted == 1) among 2");
  const std::string bad = write("bad", "shock_x,shock_y,accepted\n0,abc,1\n");
  EXPECT_EQ(error_of(bad), bad + ":2: column 'shock_y': expected a number, got 'abc'");
}
