// The shockfit executable and its files: outputs of a run, shock.csv read
// back, and the error paths (exit 2 with a clear message).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/shock_csv.hpp"
#include "scratch.hpp"
#include "shockfit/locate.hpp"
#include "synthetic.hpp"

namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  return test_support::fresh_dir("shockfit_test_" + std::to_string(::getpid()) + "_" + name);
}

struct Outcome {
  int code;
  std::string err;
};

Outcome run(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = std::string(BIN_DIR) + "/shockfit " + args + " > /dev/null 2> " + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, scene::read_file(err.string())};
}

std::string wedge_case() { return std::string(SOURCE_DIR) + "/pipeline/cases/wedge_M3_10.yaml"; }

// The exact oblique shock of the wedge_M3_10 case on a coarse lattice.
scene::Lattice wedge_lattice(const scene::Scene& s, double h) {
  const double theta = s.body->angle_deg * std::numbers::pi / 180.0;
  const double beta = *scene::oblique_shock_beta(s.freestream.mach, theta, s.freestream.gamma);
  const double r2 = scene::oblique_density_ratio(s.freestream.mach, beta, s.freestream.gamma);
  scene::Lattice lat = shockfit_test::domain_lattice(s, h);
  shockfit_test::fill(lat, "volume_fraction", [&](double x, double y) {
    return y * std::cos(beta) - x * std::sin(beta) > 0 ? 0.1 : 0.1 * r2;
  }, 0.0, 1);
  return lat;
}

bool has_gnuplot() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

}  // namespace

TEST(Cli, WritesOutputs) {
  const fs::path dir = temp_dir("outputs");
  const scene::Scene s = scene::load_scene(wedge_case());
  scene::write_vti(wedge_lattice(s, 0.01), (dir / "fields.vti").string());
  const Outcome r = run(wedge_case() + " --fields " + (dir / "fields.vti").string() + " --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(dir / "out" / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("shock"), "attached");
  EXPECT_EQ(j.at("field"), "volume_fraction");
  EXPECT_EQ(j.at("stations"), s.shockfit.stations);
  for (const char* key : {"shock_angle_deg", "shock_angle_ci_deg", "standoff", "standoff_ci", "stations_accepted"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j.at("standoff").is_null());
  const double beta = *scene::oblique_shock_beta(3.0, 10.0 * std::numbers::pi / 180.0, 1.4) * 180.0 / std::numbers::pi;
  constexpr double kCoarseTolDeg = 0.2;  // h = L/100
  EXPECT_NEAR(j.at("shock_angle_deg").get<double>(), beta, kCoarseTolDeg);

  const auto rows = scene::read_shock_csv((dir / "out" / "shock.csv").string()).rows;
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(s.shockfit.stations));
  int accepted = 0;
  for (const auto& f : rows) accepted += f.accepted ? 1 : 0;
  EXPECT_EQ(accepted, j.at("stations_accepted").get<int>());
  std::ifstream csv(dir / "out" / "shock.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "station,surface_x,surface_y,normal_x,normal_y,shock_x,shock_y,distance,ci,fit_error,accepted");
  if (has_gnuplot()) {
    EXPECT_GT(fs::file_size(dir / "out" / "shock.png"), 1000u);
    EXPECT_GT(fs::file_size(dir / "out" / "profile.png"), 1000u);
  }
  for (const auto& e : fs::directory_iterator(dir / "out"))
    EXPECT_NE(e.path().filename().string().front(), '.') << "temporary left behind: " << e.path();
  fs::remove_all(dir);
}

TEST(Cli, EmptyFieldFileExits2) {
  const fs::path dir = temp_dir("empty");
  std::ofstream(dir / "empty.vti").close();
  const Outcome r = run(wedge_case() + " --fields " + (dir / "empty.vti").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("empty.vti: not a lattice .vti file: file is empty"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
  fs::remove_all(dir);
}

TEST(Cli, MalformedFieldFileExits2) {
  const fs::path dir = temp_dir("malformed");
  scene::write_file_atomic((dir / "bad.vti").string(), "<VTKFile>\n<ImageData nonsense>\n");
  const Outcome r = run(wedge_case() + " --fields " + (dir / "bad.vti").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.vti: not a lattice .vti file: no <ImageData"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, MissingFieldFileExits2) {
  const fs::path dir = temp_dir("missing");
  const Outcome r = run(wedge_case() + " --fields " + (dir / "nope.vti").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nope.vti: fields file not found"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, UsageErrorsExit2) {
  const fs::path dir = temp_dir("usage");
  Outcome r = run(wedge_case(), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--fields is required"), std::string::npos) << r.err;
  r = run(wedge_case() + " --fields x.vti --out o --field pressure", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--field 'pressure': expected one of"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(ShockCsv, RoundTrip) {
  const fs::path dir = temp_dir("roundtrip");
  const scene::Scene s = scene::load_scene(wedge_case());
  const scene::Lattice lat = wedge_lattice(s, 0.02);
  const shockfit::ShockResult r = shockfit::locate_shock(s, lat);
  shockfit::write_outputs(s, lat, r, (dir / "out").string());
  const auto rows = scene::read_shock_csv((dir / "out" / "shock.csv").string()).rows;
  ASSERT_EQ(rows.size(), r.stations.size());
  constexpr double kPrinted = 1e-9;  // 12 significant digits
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].station, r.stations[i].station);
    EXPECT_EQ(rows[i].accepted, r.stations[i].accepted);
    if (rows[i].accepted) {
      EXPECT_NEAR(rows[i].shock.x, r.stations[i].shock.x, kPrinted);
      EXPECT_NEAR(rows[i].shock.y, r.stations[i].shock.y, kPrinted);
      EXPECT_NEAR(rows[i].ci, r.stations[i].ci, kPrinted);
    }
  }
  fs::remove_all(dir);
}

TEST(ShockCsv, Errors) {
  const fs::path dir = temp_dir("csv_errors");
  const std::string path = (dir / "shock.csv").string();
  auto expect_error = [&](const std::string& content, const std::string& message) {
    scene::write_file_atomic(path, content);
    try {
      (void)scene::read_shock_csv(path);
      ADD_FAILURE() << "no error for: " << content;
    } catch (const scene::InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path, 0), 0u) << what;
      EXPECT_NE(what.find(message), std::string::npos) << what;
    }
  };
  expect_error("", "shock file is empty");
  expect_error("station,shock_x,accepted\n0,1,1\n", ":1: missing column 'shock_y'");
  expect_error("shock_x,shock_y,accepted\n", "shock file has a header but no rows");
  expect_error("shock_x,shock_y,accepted\n1,2\n",
               ":2: no field for column 'accepted' (2 fields, the header has 3)");
  expect_error("shock_x,shock_y,accepted\n1,abc,1\n",
               ":2: column 'shock_y': expected a number, got 'abc'");
  expect_error("shock_x,shock_y,accepted\n1,2,yes\n",
               "column 'accepted': expected a number, got 'yes'");
  expect_error("shock_x,shock_y,accepted\n1,2,3\n", "column 'accepted': expected 1 or 0");
  expect_error("shock_x,shock_y,accepted\nnan,2,1\n",
               "accepted row with a non-finite shock_x or shock_y");
  const std::string absent = (dir / "absent.csv").string();
  try {
    (void)scene::read_shock_csv(absent);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(absent + ": shock file not found"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}
