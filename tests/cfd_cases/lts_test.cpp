// Local time stepping against time-accurate stepping on a small graded
// blockMesh wedge (the real rhoCentralFoam; a few thousand steps in all).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "case_setup.hpp"
#include "cfd/foam_reader.hpp"
#include "cfd/run_case.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "test_util.hpp"

namespace {

// LTS and time-accurate steady wall pressure ratios agree within this
// (measured 0.06 % with smoothing 0.02 and 0.15 % with 1 on this grid; the
// steady state does not depend on the time step, only the noise around it).
constexpr double kLtsWallTol = 0.005;
// Cells and height grading of the test grid: cells 8x smaller at the wall
// than at the top, so the smallest cell's step is far below the typical one
// and LTS has something to gain.
constexpr long kCells = 3000;
constexpr double kGrading = 8.0;
// Iteration flow-throughs vs logged steps: the columns carry 6 digits.
constexpr double kColumnTol = 1e-5;

struct Row {
  double flow_throughs = 0;
  long steps = 0;
};

std::vector<Row> history_rows(const std::string& csv) {
  std::istringstream in(scene::read_file(csv));
  std::string line;
  std::getline(in, line);  // header: time,flow_throughs,wall_seconds,steps,...
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string time, ft, wall, steps;
    std::getline(f, time, ',');
    std::getline(f, ft, ',');
    std::getline(f, wall, ',');
    std::getline(f, steps, ',');
    rows.push_back({std::stod(ft), std::stol(steps)});
  }
  return rows;
}

TEST(Lts, ReachesTheTimeAccurateSteadyStateJudgedPerIterationWindow) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0);
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, kCells, d + "/mesh", kGrading);
  cfd::CaseOptions ta;
  ta.local_time_stepping = false;
  const cfd::CaseResult euler = cfd::run_case(s, d + "/mesh", d + "/euler", ta);
  cfd::CaseOptions o;
  o.local_time_stepping = true;
  const cfd::CaseResult lts = cfd::run_case(s, d + "/mesh", d + "/lts", o);
  ASSERT_TRUE(euler.steady_state_reached);
  ASSERT_TRUE(lts.steady_state_reached);
  EXPECT_NEAR(lts.wall_pressure_ratio, euler.wall_pressure_ratio,
              kLtsWallTol * euler.wall_pressure_ratio);

  // Judged per window of N iterations: the written times are N steps apart
  // (the first row compares the first two written times), and progress is
  // the step count over the iterations per flow-through.
  const cfd::Mesh2D mesh = cfd::read_mesh_2d(d + "/mesh");
  const double lts_co = s.cfd.max_co * cfd::kLtsCourantFactor;
  const long per_ft = cfd::lts_steps_per_flow_through(mesh, cfd::freestream(s), lts_co,
                                                      scene::scene_domain(s).width());
  const long window = std::lround(s.cfd.write_interval * static_cast<double>(per_ft));
  const std::vector<Row> rows = history_rows(lts.history_csv);
  ASSERT_GE(rows.size(), static_cast<std::size_t>(s.cfd.steady_checks));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].steps, static_cast<long>(k + 2) * window) << "row " << k;
    EXPECT_NEAR(rows[k].flow_throughs,
                static_cast<double>(rows[k].steps) / static_cast<double>(per_ft),
                kColumnTol * rows[k].flow_throughs)
        << "row " << k;
  }
  EXPECT_GE(rows.back().flow_throughs, s.cfd.min_time);
  // LTS runs at a fraction of max_co (at max_co itself a wedge's captured
  // shock cycles without settling); time-accurate stepping at max_co.
  const auto max_co_of = [](const std::string& case_dir) {
    const std::string dict = scene::read_file(case_dir + "/system/controlDict");
    const auto at = dict.find("\nmaxCo");
    if (at == std::string::npos) return scene::kNaN;
    std::istringstream in(dict.substr(at + 6));
    double v = scene::kNaN;
    in >> v;
    return v;
  };
  EXPECT_DOUBLE_EQ(max_co_of(d + "/lts"), lts_co);
  EXPECT_DOUBLE_EQ(max_co_of(d + "/euler"), s.cfd.max_co);
  // Not asserted: fewer steps than time-accurate. On this graded blockMesh
  // grid LTS with the default smoothing (1) takes ~1700 steps against ~920
  // (the body force wobbles just above force_tol until the plateau rule
  // applies), with 0.02 ~770; on meshgen grids it takes 1.3-3.5x less CPU
  // (docs/bench_cfd.md).
}

}  // namespace
