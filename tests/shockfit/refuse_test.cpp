// shockfit refuses a lattice without a single finite value (exit 2, one
// line naming the file), and hostile .vti headers without allocating.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "scene/errors.hpp"
#include "scene/lattice.hpp"

namespace fs = std::filesystem;

namespace {

using test_support::CliRun;

CliRun shockfit(const std::string& args) {
  return test_support::run_cli(test_support::stage_exe("shockfit"), args);
}
std::string fresh(const std::string& name) {
  return test_support::fresh_dir("shockfit_refuse_" + name);
}

}  // namespace

TEST(Refuse, AllNanFieldsAreAnInputError) {
  const std::string dir = fresh("nan");
  const std::string scene =
      test_support::write_scene(dir, "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  scene::Lattice lat(20, 10, -0.2, 0.0, 0.06, 0.05);
  lat.add("volume_fraction", std::nan(""));
  lat.add("rho", std::nan(""));
  scene::write_vti(lat, dir + "/nan.vti");
  const CliRun r = shockfit(scene + " --fields " + dir + "/nan.vti --out " + dir + "/out");
  test_support::expect_refusal(r, dir + "/nan.vti: every value of every field is NaN or infinite");
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
