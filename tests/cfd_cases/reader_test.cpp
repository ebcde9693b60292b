// The OpenFOAM ASCII reader on small hand-written files; no OpenFOAM needed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cfd/foam_reader.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "test_util.hpp"

namespace {

const char* kHeader = "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n    object %s;\n}\n";

std::string header(const std::string& cls, const std::string& obj) {
  char buf[256];
  std::snprintf(buf, sizeof buf, kHeader, cls.c_str(), obj.c_str());
  return buf;
}

TEST(Reader, ScalarFieldUniformAndNonuniform) {
  const std::string d = cfd_test::scratch_dir();
  scene::write_file_atomic(d + "/a", header("volScalarField", "a") +
                                         "dimensions [0 0 0 0 0 0 0];\n// comment\ninternalField   uniform 1.5;\n");
  scene::write_file_atomic(d + "/b", header("volScalarField", "b") +
                                         "internalField nonuniform List<scalar> 3\n(\n1\n-2.5e-3\n7\n)\n;\n"
                                         "boundaryField { inlet { type fixedValue; value uniform 1; } }\n");
  EXPECT_EQ(cfd::read_scalar_field(d + "/a", 2), (std::vector<double>{1.5, 1.5}));
  EXPECT_EQ(cfd::read_scalar_field(d + "/b", 3), (std::vector<double>{1, -2.5e-3, 7}));
}

TEST(Reader, VectorFieldAndNan) {
  const std::string d = cfd_test::scratch_dir();
  scene::write_file_atomic(d + "/U", header("volVectorField", "U") +
                                         "internalField nonuniform List<vector> 2\n(\n(3 0 0)\n(nan -1 0)\n)\n;\n");
  const auto u = cfd::read_vector_field(d + "/U", 2);
  EXPECT_EQ(u[0][0], 3.0);
  EXPECT_TRUE(std::isnan(u[1][0]));
  EXPECT_EQ(u[1][1], -1.0);
}

TEST(Reader, WrongCellCountNamesFileAndLine) {
  const std::string d = cfd_test::scratch_dir();
  scene::write_file_atomic(d + "/p", header("volScalarField", "p") + "internalField nonuniform List<scalar> 2\n(\n1\n2\n)\n;\n");
  try {
    (void)cfd::read_scalar_field(d + "/p", 3);
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_EQ(std::string(e.what()), d + "/p:8: internalField has 2 values, the mesh 3 cells");
  }
}

TEST(Reader, BinaryFormatIsRejected) {
  const std::string d = cfd_test::scratch_dir();
  scene::write_file_atomic(d + "/p", "FoamFile\n{\n format binary;\n class volScalarField;\n}\n");
  try {
    (void)cfd::read_scalar_field(d + "/p", 3);
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("binary format"), std::string::npos) << e.what();
  }
}

TEST(Reader, TimeDirsSortedNumerically) {
  const std::string d = cfd_test::scratch_dir();
  for (const char* t : {"0", "0.orig", "0.5", "10", "2", "constant"}) std::filesystem::create_directories(d + "/" + t);
  const auto ts = cfd::time_dirs(d);
  ASSERT_EQ(ts.size(), 3u);
  EXPECT_EQ(ts[0].name, "0.5");
  EXPECT_EQ(ts[1].name, "2");
  EXPECT_EQ(ts[2].name, "10");
}

}  // namespace
