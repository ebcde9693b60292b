// shockfit refuses a lattice without a single finite value (exit 2, one
// line naming the file), and hostile .vti headers without allocating.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/errors.hpp"
#include "scene/lattice.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  int code = -1;
  std::string err;
};

Result shockfit(const std::string& args) {
  Result r;
  FILE* p = popen((std::string(BIN_DIR) + "/shockfit " + args + " 2>&1 >/dev/null").c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.err += buf.data();
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("shockfit_refuse_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

}  // namespace

TEST(Refuse, AllNanFieldsAreAnInputError) {
  const std::string dir = fresh("nan");
  const std::string scene = dir + "/scene.yaml";
  std::ofstream(scene) << "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n";
  scene::Lattice lat(20, 10, -0.2, 0.0, 0.06, 0.05);
  lat.add("volume_fraction", std::nan(""));
  lat.add("rho", std::nan(""));
  scene::write_vti(lat, dir + "/nan.vti");
  const Result r = shockfit(scene + " --fields " + dir + "/nan.vti --out " + dir + "/out");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(dir + "/nan.vti: every value of every field is NaN or infinite"),
            std::string::npos)
      << r.err;
}

TEST(Refuse, HostileVtiHeadersAreInputErrors) {
  const std::string dir = fresh("header");
  const auto expect_bad = [&](const std::string& header, const std::string& needle) {
    const std::string path = dir + "/h.vti";
    std::ofstream(path) << "<VTKFile type=\"ImageData\">\n  <ImageData " << header
                        << ">\n<DataArray Name=\"rho\">\n1 2\n</DataArray>\n";
    try {
      (void)scene::read_vti(path);
      FAIL() << "no error for " << header;
    } catch (const scene::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_bad(R"(WholeExtent="0 99999999999 0 1 0 0" Origin="0 0 0" Spacing="1 1 1")", "too large");
  expect_bad(R"(WholeExtent="0 50000 0 50000 0 0" Origin="0 0 0" Spacing="1 1 1")",
             "more values than the file");
  expect_bad(R"(WholeExtent="0 1 0 2 0 0" Origin="inf 0 0" Spacing="1 1 1")",
             "Origin x 'inf' is not finite");
  expect_bad(R"(WholeExtent="0 1 0 2 0 0" Origin="0 0 0" Spacing="-1 1 1")",
             "Spacing must be positive");
}
