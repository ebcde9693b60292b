// CPU accounting of a run: the solver's CPU (every rank under mpirun) and
// decomposePar/reconstructPar's, beside wall time, in CaseResult and
// summary.json.
#include <gtest/gtest.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "cfd/run_case.hpp"
#include "scene/io.hpp"
#include "test_util.hpp"

namespace {

// With the ranks counted, a parallel run costs about the serial CPU or more
// (MPI adds work); without them it would be mpirun's own few milliseconds.
constexpr double kRanksCounted = 0.5;
constexpr double kMicro = 1e6;

void expect_summary(const cfd::CaseResult& r) {
  const nlohmann::json j = nlohmann::json::parse(scene::read_file(r.case_dir + "/summary.json"));
  EXPECT_DOUBLE_EQ(j.at("cpu_seconds").get<double>(), r.cpu_seconds);
  EXPECT_DOUBLE_EQ(
      j.at("cpu_us_per_cell_step").get<double>(),
      r.cpu_seconds * kMicro / (static_cast<double>(r.cells) * static_cast<double>(r.steps)));
  EXPECT_TRUE(j.contains("wall_seconds"));
}

}  // namespace

TEST(CpuAccounting, SerialAndParallelRunsReportTheirCpu) {
  // steady_tol tiny: both runs go to end_time and do the same steps.
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0, "{end_time: 0.6, steady_tol: 1e-12}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 2000, d + "/mesh");
  const cfd::CaseResult serial = cfd::run_case(s, d + "/mesh", d + "/serial", {});
  cfd::CaseOptions o;
  o.np = 2;
  const cfd::CaseResult par = cfd::run_case(s, d + "/mesh", d + "/parallel", o);
  EXPECT_GT(serial.cpu_seconds, 0.0);
  EXPECT_GT(par.cpu_seconds, kRanksCounted * serial.cpu_seconds);
  expect_summary(serial);
  expect_summary(par);
  std::cout << "cells " << serial.cells << ", steps " << serial.steps << "\n"
            << "serial:   wall " << serial.wall_seconds << " s, cpu " << serial.cpu_seconds
            << " s\n"
            << "parallel: wall " << par.wall_seconds << " s, cpu " << par.cpu_seconds
            << " s (np 2)\n";
}
