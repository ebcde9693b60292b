// One scheme per comparison: when it is needed and what a grid solved
// again is charged.
#include "pipeline/one_scheme.hpp"

#include <gtest/gtest.h>

#include <tuple>

#include "pipeline/strip_fallback.hpp"

using pipeline::GridRun;

namespace {
const std::string kRobust = "Tadmor/Minmod";

GridRun run(const std::string& family, double level, const std::string& scheme) {
  GridRun r;
  std::tie(r.family, r.level, r.scheme) = std::tie(family, level, scheme);
  return r;
}
}  // namespace

TEST(OneScheme, NeededOnlyWhenSomeGridOfTheFamilyEndedOnTheRobustSchemeBesideAnother) {
  const std::vector<GridRun> own{run("uniform", 2, "Kurganov/vanLeer"),
                                 run("uniform", 1, "Kurganov/vanLeer")};
  const std::vector<GridRun> fell_back{run("clustered", 2, "Kurganov/vanLeer"),
                                       run("clustered", 1, kRobust)};
  const std::vector<GridRun> all_robust{run("clustered", 2, kRobust), run("clustered", 1, kRobust)};
  EXPECT_FALSE(pipeline::needs_one_scheme(own, kRobust));
  EXPECT_TRUE(pipeline::needs_one_scheme(fell_back, kRobust));
  EXPECT_FALSE(pipeline::needs_one_scheme(all_robust, kRobust));
  // Grids without a CFD run carry no scheme.
  EXPECT_FALSE(
      pipeline::needs_one_scheme({run("uniform", 2, ""), run("uniform", 1, kRobust)}, kRobust));
  // Two schemes, neither the robust one (a scene's own mix): not this rule's to mend.
  EXPECT_FALSE(pipeline::needs_one_scheme(
      {run("clustered", 2, "Kurganov/Minmod"), run("clustered", 1, "Kurganov/vanLeer")}, kRobust));
}

TEST(OneScheme, AFamilysSchemeIsNamedOrCalledMixed) {
  EXPECT_EQ(pipeline::family_scheme({run("uniform", 2, kRobust), run("uniform", 1, kRobust)}),
            kRobust);
  EXPECT_EQ(
      pipeline::family_scheme({run("uniform", 2, "Kurganov/vanLeer"), run("uniform", 1, kRobust)}),
      "mixed (Kurganov/vanLeer, Tadmor/Minmod)");
  EXPECT_EQ(pipeline::family_scheme({run("uniform", 1, "")}), "");
  EXPECT_EQ(pipeline::family_scheme({}), "");
}

TEST(OneScheme, AGridRunAgainIsChargedBothRunsAndSaysWhy) {
  GridRun first = run("uniform", 2, "Kurganov/vanLeer");
  first.cfd_cpu_seconds = 3.5;
  first.cfd_wall_seconds = 4.0;
  first.mesh_cpu_seconds = 0.5;
  first.steps = 1000;
  first.primary_error = 0.04;
  first.mesh_name = first.case_name = "uniform_h2";
  GridRun again = run("uniform", 2, kRobust);
  again.cfd_cpu_seconds = 9.0;
  again.cfd_wall_seconds = 10.0;
  again.mesh_cpu_seconds = 0.5;
  again.steps = 2500;
  again.primary_error = 0.06;
  again.mesh_name = "uniform_h2";
  again.case_name = "uniform_h2_robust";
  const GridRun charged = pipeline::charge_first_run(first, again, "solved again");
  EXPECT_DOUBLE_EQ(charged.cfd_cpu_seconds, 12.5);
  EXPECT_DOUBLE_EQ(charged.cfd_wall_seconds, 14.0);
  EXPECT_EQ(charged.steps, 3500);
  // The mesh is shared: meshed once, charged once.
  EXPECT_DOUBLE_EQ(charged.mesh_cpu_seconds, 0.5);
  // The result is the second run's: its error, scheme and case.
  EXPECT_DOUBLE_EQ(charged.primary_error, 0.06);
  EXPECT_EQ(charged.scheme, kRobust);
  EXPECT_EQ(charged.case_name, "uniform_h2_robust");
  EXPECT_NE(
      charged.note.find("solved again; its first run (Kurganov/vanLeer, 3.5 CPU s) is charged too"),
      std::string::npos)
      << charged.note;
  // A grid meshed again is charged its first mesh too.
  again.mesh_name = "uniform_h2_isotropic";
  EXPECT_DOUBLE_EQ(pipeline::charge_first_run(first, again, "meshed again").mesh_cpu_seconds, 1.0);
}

TEST(StripFallback,
     OnlyAStripGridThatEndedOnTheRobustSchemeAfterDivergingCallsForTheIsotropicBand) {
  GridRun r = run("clustered", 2, kRobust);
  r.strips = true;
  r.fell_back = true;
  EXPECT_TRUE(pipeline::strips_diverged(r, kRobust));
  GridRun bridged = r;  // the bridge returned it to the scene's scheme
  bridged.scheme = "Kurganov/vanLeer";
  EXPECT_FALSE(pipeline::strips_diverged(bridged, kRobust));
  GridRun isotropic = r;
  isotropic.strips = false;
  EXPECT_FALSE(pipeline::strips_diverged(isotropic, kRobust));
  GridRun robust_by_choice = r;  // the scene asked for the robust scheme; it never diverged
  robust_by_choice.fell_back = false;
  EXPECT_FALSE(pipeline::strips_diverged(robust_by_choice, kRobust));
}
