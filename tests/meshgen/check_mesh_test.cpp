// checkMesh's verdict from its log: which failed checks are only quality
// warnings (accepted) and which make the mesh unusable (a RunError).
#include <gtest/gtest.h>

#include <string>

#include "foam_export.hpp"

namespace {

// The parts of a checkMesh log that the verdict reads.
std::string check_log(const std::string& failures, int failed) {
  std::string log =
      "Checking geometry...\n    Mesh non-orthogonality Max: 35.3 average: 8.1\n"
      "    Max skewness = 0.78 OK.\n" +
      failures + "\n";
  log += failed == 0 ? "Mesh OK.\n" : "Failed " + std::to_string(failed) + " mesh checks.\n";
  return log;
}

}  // namespace

TEST(CheckMesh, MeshOk) {
  const meshgen::CheckMeshReport r = meshgen::parse_check_mesh(check_log("", 0));
  EXPECT_TRUE(r.ok);
  EXPECT_FALSE(r.warnings_only);
  EXPECT_DOUBLE_EQ(r.max_non_orthogonality, 35.3);
}

TEST(CheckMesh, SkewnessAndAspectRatioAreWarnings) {
  const meshgen::CheckMeshReport r = meshgen::parse_check_mesh(
      check_log(" ***Max skewness = 5.2, 3 highly skew faces detected which may impair the quality "
                "of the results\n"
                " ***High aspect ratio cells found, Max aspect ratio: 1200, number of cells 4\n",
                2));
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.warnings_only);
  EXPECT_NE(r.failures.find("highly skew faces"), std::string::npos);
}

TEST(CheckMesh, AnyOtherFailureIsFatal) {
  const meshgen::CheckMeshReport r =
      meshgen::parse_check_mesh(check_log(" ***Max skewness = 5.2, 3 highly skew faces detected "
                                          "which may impair the quality of the results\n"
                                          " ***Zero or negative cell volume detected.  Minimum "
                                          "negative volume: -1e-09, Number of negative volume "
                                          "cells: 1\n",
                                          2));
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.warnings_only);
  // Failed without a *** line: no judgement to trust, fatal.
  EXPECT_FALSE(meshgen::parse_check_mesh(check_log("", 1)).warnings_only);
}
