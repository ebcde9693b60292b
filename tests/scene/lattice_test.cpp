// Lattice fields: .vti round trip, interpolation, and bad files.
#include "scene/lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
fs::path temp_dir(const std::string& name) {
  return test_support::fresh_dir("scene_test_" + name);
}
}  // namespace

TEST(Lattice, VtiRoundTripIsExactToTenDigits) {
  scene::Lattice lat(7, 5, -0.2, 0.0, 0.1, 0.05);
  auto& a = lat.add("volume_fraction");
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = std::sin(0.37 * static_cast<double>(k)) / 3.0;
  a[3] = std::numeric_limits<double>::quiet_NaN();  // inside the body
  lat.add("inside_body", 0.0)[3] = 1.0;
  const auto path = (temp_dir("vti") / "f.vti").string();
  scene::write_vti(lat, path);
  const auto back = scene::read_vti(path);
  EXPECT_EQ(back.nx, 7);
  EXPECT_EQ(back.ny, 5);
  EXPECT_DOUBLE_EQ(back.x0, -0.2);
  EXPECT_DOUBLE_EQ(back.dy, 0.05);
  ASSERT_TRUE(back.has("volume_fraction"));
  const auto& b = back.field("volume_fraction");
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (k == 3) {
      EXPECT_TRUE(std::isnan(b[k]));
    } else {
      EXPECT_NEAR(b[k], a[k], 1e-10 * std::max(1.0, std::abs(a[k])));
    }
  }
}

TEST(Lattice, BilinearSampleIsExactForLinearFields) {
  scene::Lattice lat(10, 8, 0.0, 0.0, 0.5, 0.25);
  auto& f = lat.add("p");
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) f[lat.index(i, j)] = 2.0 * lat.xc(i) - 3.0 * lat.yc(j) + 1.0;
  double v = 0;
  ASSERT_TRUE(lat.sample("p", 2.13, 1.07, v));
  EXPECT_NEAR(v, 2.0 * 2.13 - 3.0 * 1.07 + 1.0, 1e-12);
  EXPECT_FALSE(lat.sample("p", -1.0, 0.5, v));  // outside
  EXPECT_THROW(lat.sample("nope", 1.0, 1.0, v), scene::InputError);
}

TEST(Lattice, SampleRefusesNaNNeighbours) {
  scene::Lattice lat(4, 4, 0, 0, 1, 1);
  auto& f = lat.add("rho", 1.0);
  f[lat.index(1, 1)] = std::numeric_limits<double>::quiet_NaN();
  double v = 0;
  EXPECT_FALSE(lat.sample("rho", 1.6, 1.6, v));
  EXPECT_TRUE(lat.sample("rho", 3.2, 3.2, v));
}

TEST(Lattice, BadFilesAreClearErrors) {
  const auto d = temp_dir("bad");
  const auto empty = (d / "empty.vti").string();
  scene::write_file_atomic(empty, "");
  try {
    scene::read_vti(empty);
    FAIL();
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("file is empty"), std::string::npos) << e.what();
  }
  const auto junk = (d / "junk.vti").string();
  scene::write_file_atomic(junk, "<VTKFile>hello</VTKFile>");
  EXPECT_THROW(scene::read_vti(junk), scene::InputError);
  const auto shortf = (d / "short.vti").string();
  scene::write_file_atomic(shortf,
      "<ImageData WholeExtent=\"0 2 0 2 0 0\" Origin=\"0 0 0\" Spacing=\"1 1 1\">"
      "<DataArray type=\"Float64\" Name=\"rho\" format=\"ascii\">1 2 3</DataArray>");
  try {
    scene::read_vti(shortf);
    FAIL();
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has 3 values, expected 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene::read_vti((d / "missing.vti").string()), scene::InputError);
}
