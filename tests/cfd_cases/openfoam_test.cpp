// The real rhoCentralFoam on small blockMesh wedge grids (about 2-5k cells,
// a few hundred steps each).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "case_setup.hpp"
#include "cfd/foam_reader.hpp"
#include "cfd/run_case.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "test_util.hpp"

namespace {
namespace fs = std::filesystem;
using scene::kDeg;

// Coarse grid, M3/10: the wall pressure ratio is within this of theory
// (measured 0.1-0.2 % at 5k cells).
constexpr double kCoarseWallTol = 0.01;
// Serial vs parallel: files carry 12 significant digits; the decomposition
// only reorders sums, so fields agree far below this.
constexpr double kParallelTol = 1e-8;
// Resampled free stream: exact up to the written digits.
constexpr double kFreestreamTol = 1e-6;
// A run continued from a written state against one run straight through:
// the state carries 12 significant digits and the restart's first step
// differs, which the transient carries on (1.8e-6 measured at 1.2
// flow-throughs); far below the coarse grid's discretisation error.
constexpr double kContinuedTol = 1e-5;
// LTS and time-accurate steady wall pressures agree within this.
constexpr double kLtsTol = 0.01;

// With the ranks counted, a parallel run costs about the serial CPU or more
// (MPI adds work); without them it would be mpirun's own few milliseconds.
constexpr double kRanksCounted = 0.5;
constexpr double kMicro = 1e6;

// The run's CPU accounting as summary.json reports it.
void expect_cpu_summary(const cfd::CaseResult& r) {
  const nlohmann::json j = nlohmann::json::parse(scene::read_file(r.case_dir + "/summary.json"));
  EXPECT_DOUBLE_EQ(j.at("cpu_seconds").get<double>(), r.cpu_seconds);
  EXPECT_DOUBLE_EQ(
      j.at("cpu_us_per_cell_step").get<double>(),
      r.cpu_seconds * kMicro / (static_cast<double>(r.cells) * static_cast<double>(r.steps)));
  EXPECT_TRUE(j.contains("wall_seconds"));
}

double exact_ratio(double mach, double deg) {
  return scene::oblique_pressure_ratio(mach, *scene::oblique_shock_beta(mach, deg * kDeg, 1.4), 1.4);
}

TEST(Case, InstantiationFollowsTheScene) {
  // Time-accurate: sim_time is checked against the flow-through time.
  const scene::Scene s = cfd_test::wedge_scene(
      3.0, 10.0, "{max_co: 0.25, end_time: 0.2, write_interval: 0.1, local_time_stepping: false}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 2000, d + "/mesh");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  const std::string c = d + "/case";
  for (const char* f : {"0.orig/U", "0/U", "constant/polyMesh/faces", "constant/thermophysicalProperties",
                        "system/controlDict", "log.rhoCentralFoam", "history.csv", "summary.json", "scene.yaml"})
    EXPECT_TRUE(fs::exists(c + "/" + f)) << f;
  EXPECT_TRUE((fs::status(c + "/Allrun").permissions() & fs::perms::owner_exec) != fs::perms::none);
  const std::string control = scene::read_file(c + "/system/controlDict");
  EXPECT_NE(control.find("maxCo           0.25;"), std::string::npos);
  EXPECT_NE(control.find("stopAt    endTime;"), std::string::npos) << "restored after the run";
  EXPECT_NE(scene::read_file(c + "/0/U").find("uniform (3 0 0)"), std::string::npos);
  // R = RR/molWeight = 1/gamma and Cp = 1/(gamma - 1).
  const std::string thermo = scene::read_file(c + "/constant/thermophysicalProperties");
  EXPECT_NE(thermo.find("molWeight       11640.258;"), std::string::npos) << thermo;
  EXPECT_NE(thermo.find("Cp              2.5;"), std::string::npos);
  // The free stream upstream of the apex: rho = gamma p / T = 1.4 exactly.
  const scene::Lattice lat = cfd::resample_to_lattice(s, c, 60, 40);
  double rho = 0, mach = 0;
  ASSERT_TRUE(lat.sample("rho", -0.15, 0.5, rho));
  ASSERT_TRUE(lat.sample("mach", -0.15, 0.5, mach));
  EXPECT_NEAR(rho, 1.4, kFreestreamTol);
  EXPECT_NEAR(mach, 3.0, kFreestreamTol);
  EXPECT_NEAR(r.sim_time, 0.2 * r.flow_through_time, 1e-9);
  EXPECT_GT(r.steps, 10);
  EXPECT_FALSE(r.steady_state_reached);
}

TEST(Case, SteadyStateIsDetectedAndTheRunStopped) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 6}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 5000, d + "/mesh");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  EXPECT_TRUE(r.steady_state_reached);
  // Stopped by the monitor well before end_time (the transient takes about
  // two flow-through times).
  EXPECT_LT(r.sim_time, 4.0 * r.flow_through_time);
  EXPECT_LT(r.final_density_change_l2, s.cfd.steady_tol);
  EXPECT_LT(r.final_force_change, s.cfd.force_tol);
  const double exact = exact_ratio(3.0, 10.0);
  EXPECT_NEAR(r.wall_pressure_ratio, exact, kCoarseWallTol * exact);
  // History: header plus one row per written time after the first.
  std::ifstream in(r.history_csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "time,flow_throughs,wall_seconds,steps,drho_l2,drho_max,dforce,force_x,force_y,"
            "wall_pressure_ratio,shock_x,dshock,shock_drift,shock_cell");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    // An attached wedge has no shock ahead of its apex: the shock columns
    // are empty.
    EXPECT_EQ(line.substr(line.size() - 4), ",,,,") << line;
  }
  EXPECT_GE(rows, 2 * s.cfd.steady_checks);
  EXPECT_TRUE(fs::exists(r.case_dir + "/history.png"));
  // Resampled: NaN inside the wedge, flagged; post-shock Mach below M.
  const scene::Lattice lat = cfd::resample_to_lattice(s, r.case_dir, 120, 80);
  double inside = 0, v = 0;
  ASSERT_TRUE(lat.sample("inside_body", 0.8, 0.05, inside));
  EXPECT_EQ(inside, 1.0);
  EXPECT_FALSE(lat.sample("rho", 0.8, 0.05, v));
  ASSERT_TRUE(lat.sample("mach", 0.8, 0.2, v));
  EXPECT_NEAR(v, scene::oblique_downstream_mach(3.0, *scene::oblique_shock_beta(3.0, 10 * kDeg, 1.4), 10 * kDeg, 1.4), 0.05);
}

// One serial and one 2-rank run of the same case: the same fields, and each
// run's CPU (the solver's, every rank under mpirun, and decomposePar /
// reconstructPar's) beside wall time in CaseResult and summary.json.
TEST(Case, ParallelEqualsSerialAndBothReportTheirCpu) {
  // steady_tol tiny: both runs go to end_time, so they end at the same time.
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 0.6, steady_tol: 1e-12}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 2000, d + "/mesh");
  const cfd::CaseResult serial = cfd::run_case(s, d + "/mesh", d + "/serial", {});
  cfd::CaseOptions o;
  o.np = 2;
  const cfd::CaseResult par = cfd::run_case(s, d + "/mesh", d + "/parallel", o);
  EXPECT_TRUE(fs::exists(d + "/parallel/processor1"));
  EXPECT_EQ(serial.steps, par.steps);
  ASSERT_DOUBLE_EQ(serial.sim_time, par.sim_time);
  const auto t = cfd::time_dirs(d + "/serial").back().name;
  ASSERT_EQ(t, cfd::time_dirs(d + "/parallel").back().name);
  const std::size_t n = static_cast<std::size_t>(serial.cells);
  for (const char* f : {"rho", "p", "T"}) {
    const auto a = cfd::read_scalar_field(d + "/serial/" + t + "/" + f, n);
    const auto b = cfd::read_scalar_field(d + "/parallel/" + t + "/" + f, n);
    double worst = 0;
    for (std::size_t k = 0; k < n; ++k) worst = std::max(worst, std::abs(a[k] - b[k]) / std::abs(a[k]));
    EXPECT_LT(worst, kParallelTol) << f;
  }
  EXPECT_NEAR(serial.wall_pressure_ratio, par.wall_pressure_ratio, kParallelTol);
  EXPECT_GT(serial.cpu_seconds, 0.0);
  EXPECT_GT(par.cpu_seconds, kRanksCounted * serial.cpu_seconds);
  expect_cpu_summary(serial);
  expect_cpu_summary(par);
}

// A run continued from a written state (what the divergence fallback's
// bridge does) starts at that state's time: it ends where a run straight
// through ends, in about the steps of the part it ran, and its history
// begins after the state; on 2 ranks too (only that state is decomposed).
TEST(Case, AContinuedRunStartsFromTheStateItIsGiven) {
  const scene::Scene half = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 0.6, steady_tol: 1e-12}");
  const scene::Scene whole = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 1.2, steady_tol: 1e-12}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(half, 2000, d + "/mesh");
  const cfd::CaseResult straight = cfd::run_case(whole, d + "/mesh", d + "/straight", {});
  const cfd::CaseResult first = cfd::run_case(half, d + "/mesh", d + "/first", {});
  const cfd::TimeDir state = cfd::time_dirs(d + "/first").back();
  fs::create_directories(d + "/aside");
  fs::copy(d + "/first/" + state.name, d + "/aside/" + state.name, fs::copy_options::recursive);
  for (const int np : {1, 2}) {
    cfd::CaseOptions o;
    o.np = np;
    o.continue_from = d + "/aside/" + state.name;
    const std::string cdir = d + "/continued" + std::to_string(np);
    const cfd::CaseResult r = cfd::run_case(whole, d + "/mesh", cdir, o);
    EXPECT_NEAR(r.sim_time, straight.sim_time, kFreestreamTol) << np;
    EXPECT_LT(r.steps, straight.steps - first.steps / 2) << np;
    std::ifstream history(cdir + "/history.csv");
    std::string header, row;
    std::getline(history, header);
    std::getline(history, row);
    EXPECT_GT(std::stod(row.substr(row.find(',') + 1)), 0.6) << row;
    EXPECT_NEAR(r.wall_pressure_ratio, straight.wall_pressure_ratio,
                kContinuedTol * straight.wall_pressure_ratio)
        << np;
  }
}

TEST(Case, DivergenceIsRunErrorAndTheCaseIsKept) {
  // maxCo 4 is far beyond the explicit scheme's stability limit.
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{max_co: 4, end_time: 2}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 2000, d + "/mesh");
  try {
    (void)cfd::run_case(s, d + "/mesh", d + "/case", {});
    FAIL() << "expected RunError";
  } catch (const scene::RunError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("the solution diverged", 0), 0u) << m;
    EXPECT_NE(m.find(d + "/case/log.rhoCentralFoam"), std::string::npos) << m;
  }
  EXPECT_TRUE(fs::exists(d + "/case/log.rhoCentralFoam"));
  EXPECT_TRUE(fs::exists(d + "/case/system/controlDict"));
}

TEST(Case, LocalTimeSteppingReachesTheSameState) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 6}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 3000, d + "/mesh");
  cfd::CaseOptions ta;
  ta.local_time_stepping = false;
  const cfd::CaseResult euler = cfd::run_case(s, d + "/mesh", d + "/euler", ta);
  cfd::CaseOptions o;
  o.local_time_stepping = true;
  const cfd::CaseResult lts = cfd::run_case(s, d + "/mesh", d + "/lts", o);
  EXPECT_NE(scene::read_file(d + "/lts/system/fvSchemes").find("localEuler"), std::string::npos);
  EXPECT_NE(scene::read_file(d + "/lts/log.rhoCentralFoam").find("Using LTS"), std::string::npos);
  EXPECT_TRUE(euler.steady_state_reached);
  EXPECT_TRUE(lts.steady_state_reached);
  EXPECT_NEAR(lts.wall_pressure_ratio, euler.wall_pressure_ratio, kLtsTol * euler.wall_pressure_ratio);
}

TEST(Case, ForeignPatchNameIsInputError) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0);
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 500, d + "/mesh");
  std::string b = scene::read_file(d + "/mesh/constant/polyMesh/boundary");
  b.replace(b.find("    top\n"), 8, "    farField\n");
  scene::write_file_atomic(d + "/mesh/constant/polyMesh/boundary", b);
  try {
    (void)cfd::run_case(s, d + "/mesh", d + "/case", {});
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_EQ(std::string(e.what()), d + "/mesh/constant/polyMesh/boundary: patch 'farField' is not one of inlet, "
                                         "outlet, top, bottom, body (or an empty/symmetryPlane patch)");
  }
}

}  // namespace
