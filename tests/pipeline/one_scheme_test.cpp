// One scheme per comparison: when it is needed and what a grid solved
// again is charged.
#include "pipeline/one_scheme.hpp"

#include <gtest/gtest.h>

using pipeline::GridRun;

namespace {
const std::string kRobust = "Tadmor/Minmod";

GridRun run(const std::string& family, double level, const std::string& scheme) {
  GridRun r;
  r.family = family;
  r.level = level;
  r.scheme = scheme;
  return r;
}
}  // namespace

TEST(OneScheme, NeededOnlyWhenSomeGridEndedOnTheRobustSchemeBesideAnother) {
  const std::vector<GridRun> own{run("uniform", 2, "Kurganov/vanLeer"),
                                 run("uniform", 1, "Kurganov/vanLeer")};
  const std::vector<GridRun> fell_back{run("clustered", 2, "Kurganov/vanLeer"),
                                       run("clustered", 1, kRobust)};
  const std::vector<GridRun> all_robust{run("clustered", 2, kRobust), run("clustered", 1, kRobust)};
  EXPECT_FALSE(pipeline::needs_one_scheme(own, own, kRobust));
  EXPECT_TRUE(pipeline::needs_one_scheme(fell_back, own, kRobust));
  // The mix across families counts as much as within one.
  EXPECT_TRUE(pipeline::needs_one_scheme(all_robust, own, kRobust));
  EXPECT_FALSE(pipeline::needs_one_scheme(all_robust, all_robust, kRobust));
  // Grids without a CFD run carry no scheme.
  EXPECT_FALSE(pipeline::needs_one_scheme(all_robust, {run("uniform", 1, "")}, kRobust));
  // Two schemes, neither the robust one (a scene's own mix): not this rule's to mend.
  EXPECT_FALSE(pipeline::needs_one_scheme({run("clustered", 1, "Kurganov/Minmod")}, own, kRobust));
}

TEST(OneScheme, AGridSolvedAgainIsChargedBothRunsAndSaysWhy) {
  GridRun first = run("uniform", 2, "Kurganov/vanLeer");
  first.cfd_cpu_seconds = 3.5;
  first.cfd_wall_seconds = 4.0;
  first.steps = 1000;
  first.primary_error = 0.04;
  GridRun again = run("uniform", 2, kRobust);
  again.cfd_cpu_seconds = 9.0;
  again.cfd_wall_seconds = 10.0;
  again.steps = 2500;
  again.primary_error = 0.06;
  again.case_name = "uniform_h2_robust";
  const GridRun charged = pipeline::charge_first_run(first, again);
  EXPECT_DOUBLE_EQ(charged.cfd_cpu_seconds, 12.5);
  EXPECT_DOUBLE_EQ(charged.cfd_wall_seconds, 14.0);
  EXPECT_EQ(charged.steps, 3500);
  // The result is the robust run's: its error, scheme and case.
  EXPECT_DOUBLE_EQ(charged.primary_error, 0.06);
  EXPECT_EQ(charged.scheme, kRobust);
  EXPECT_EQ(charged.case_name, "uniform_h2_robust");
  EXPECT_NE(charged.note.find("Kurganov/vanLeer run (3.5 CPU s) is charged"), std::string::npos)
      << charged.note;
}
