// The verdict's arithmetic: equal-error cost ratios with intervals, the
// cheapest-cost reading of a family, Richardson extrapolation and the exact
// cell-average L1 measure on cells cut by a known line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/cost_estimate.hpp"
#include "pipeline/equal_error.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/grid_convergence.hpp"
#include "pipeline/grid_runs.hpp"
#include "scene/errors.hpp"

namespace {
using pipeline::CostError;

// error = k cost^b exactly.
std::vector<CostError> power_law(double k, double b, std::vector<double> costs, double rel_ci = 0) {
  std::vector<CostError> out;
  for (const double c : costs) {
    const double e = k * std::pow(c, b);
    out.push_back({c, e, rel_ci * e});
  }
  return out;
}

TEST(EqualError, CheapestRunAlreadyAccurateIsNotInterpolated) {
  // A cheaper run already meets the error: its cost, not an interpolation
  // across the first bracketing pair (which gave 2x instead of 1x).
  const std::vector<CostError> u{{1, 0.05, 0}, {4, 0.2, 0}, {16, 0.01, 0}};
  EXPECT_DOUBLE_EQ(pipeline::cheapest_cost_at(u, 0.1), 1.0);
  // Order of the input does not matter.
  const std::vector<CostError> shuffled{{16, 0.01, 0}, {1, 0.05, 0}, {4, 0.2, 0}};
  EXPECT_DOUBLE_EQ(pipeline::cheapest_cost_at(shuffled, 0.1), 1.0);
  // Only the finest reaches 0.02: log-log between the 4 s and 16 s runs.
  const double c = pipeline::cheapest_cost_at(u, 0.02);
  const double t = std::log(0.02 / 0.2) / std::log(0.01 / 0.2);
  EXPECT_NEAR(c, std::exp(std::log(4.0) + t * std::log(4.0)), 1e-12);
  EXPECT_TRUE(std::isnan(pipeline::cheapest_cost_at(u, 0.001)));
}

TEST(EqualError, FitRecoversPowerLaw) {
  const auto f = pipeline::fit_log_log(power_law(2.0, -0.75, {1, 3, 10, 30, 100}));
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.b, -0.75, 1e-12);
  EXPECT_NEAR(f.a, std::log(2.0), 1e-12);
  EXPECT_NEAR(f.residual_sd, 0.0, 1e-12);
  EXPECT_NEAR(std::exp(f.log_cost_at(2.0 * std::pow(10.0, -0.75))), 10.0, 1e-9);
  EXPECT_FALSE(pipeline::fit_log_log(power_law(2.0, -0.75, {1, 3})).ok) << "two runs leave no residual";
}

TEST(EqualError, ExactFamiliesGiveTheExactRatioAndAPointInterval) {
  // Same slope, the fast family reaches every error at 1/5 of the cost.
  const auto slow = power_law(1.0, -0.5, {10, 40, 160, 640});
  const auto fast = power_law(std::pow(5.0, -0.5), -0.5, {2, 8, 32, 128});
  const auto r = pipeline::cost_ratio_at_error(slow, fast, 0.05);
  EXPECT_NEAR(r.value, 5.0, 1e-9);
  EXPECT_NEAR(r.ci_low, 5.0, 1e-6);
  EXPECT_NEAR(r.ci_high, 5.0, 1e-6);
  EXPECT_EQ(pipeline::verdict_of(r), "faster");
  EXPECT_EQ(pipeline::verdict_of(pipeline::cost_ratio_at_error(fast, slow, 0.05)), "slower");
}

TEST(EqualError, AFixedCostIsAddedAfterTheFitNotFoldedIntoIt) {
  // The fast family reaches every error at 1/4 of the slow one's per-grid
  // cost and pays a fixed 20 (its predictor, as large as its middle grid's
  // cost) once. At error 0.01 the slow family costs 100, the fast one
  // 25 + 20: exactly 20/9, with a point interval since both per-grid laws
  // are exact.
  const auto slow = power_law(1.0, -1.0, {10, 20, 40, 80, 160});
  const auto fast = power_law(0.25, -1.0, {2.5, 5, 10, 20, 40});
  const auto r = pipeline::cost_ratio_at_error(pipeline::FamilyPair{slow, fast, 0.0, 20.0}, 0.01);
  EXPECT_NEAR(r.value, 100.0 / 45.0, 1e-9);
  EXPECT_NEAR(r.ci_low, r.value, 1e-6);
  EXPECT_NEAR(r.ci_high, r.value, 1e-6);
  // Folded into every run's cost, the same 20 bends the fast family's line
  // (it dominates the coarse runs): the fit no longer holds its own points
  // and the interval opens around a biased value.
  auto folded = fast;
  for (auto& run : folded) run.cost += 20.0;
  const auto bent = pipeline::cost_ratio_at_error(slow, folded, 0.01);
  // (measured: 2.14, 1.52-2.58 against the exact 2.22)
  EXPECT_GT(std::abs(bent.value / r.value - 1.0), 0.02);
  EXPECT_GT(bent.ci_high / bent.ci_low, 1.5);
}

TEST(EqualError, ScatterWidensTheIntervalAroundTheTruth) {
  // Residual scatter of ~10% on a 3x ratio: interval contains 3, lies above 1.
  auto slow = power_law(1.0, -0.5, {10, 20, 40, 80, 160});
  auto fast = power_law(std::pow(3.0, -0.5), -0.5, {2, 4, 8, 16, 32});
  const double wiggle[] = {1.1, 0.92, 1.05, 0.95, 1.08};
  for (int k = 0; k < 5; ++k) {
    slow[k].error *= wiggle[k];
    fast[k].error *= wiggle[4 - k];
  }
  const auto r = pipeline::cost_ratio_at_error(slow, fast, 0.1);
  EXPECT_LT(r.ci_low, 3.0);
  EXPECT_GT(r.ci_high, 3.0);
  EXPECT_LT(r.ci_low, r.value);
  EXPECT_GT(r.ci_high, r.value);
  EXPECT_EQ(pipeline::verdict_of(r), "faster");
  // Reproducible: the Monte Carlo is seeded.
  const auto again = pipeline::cost_ratio_at_error(slow, fast, 0.1);
  EXPECT_EQ(r.ci_low, again.ci_low);
  EXPECT_EQ(r.ci_high, again.ci_high);
}

TEST(EqualError, OverlappingNoisyFamiliesAreNotDistinguishable) {
  auto a = power_law(1.0, -0.5, {10, 20, 40, 80});
  auto b = power_law(1.05, -0.5, {10, 20, 40, 80});
  const double wiggle[] = {1.3, 0.75, 1.25, 0.8};
  for (int k = 0; k < 4; ++k) a[k].error *= wiggle[k];
  const auto r = pipeline::cost_ratio_at_error(a, b, 0.15);
  EXPECT_LT(r.ci_low, 1.0);
  EXPECT_GT(r.ci_high, 1.0);
  EXPECT_EQ(pipeline::verdict_of(r), "not distinguishable");
}

TEST(EqualError, RunErrorIntervalsWidenTheInterval) {
  const auto slow = power_law(1.0, -0.5, {10, 40, 160, 640});
  const auto fast = power_law(std::pow(5.0, -0.5), -0.5, {2, 8, 32, 128}, 0.3);
  const auto r = pipeline::cost_ratio_at_error(slow, fast, 0.05);
  EXPECT_LT(r.ci_low, 4.5);
  EXPECT_GT(r.ci_high, 5.5);
}

TEST(EqualError, UnusableFamilyGivesNoVerdict) {
  const auto slow = power_law(1.0, -0.5, {10, 40});
  const auto fast = power_law(1.0, -0.5, {2, 8, 32});
  const auto r = pipeline::cost_ratio_at_error(slow, fast, 0.05);
  EXPECT_TRUE(std::isnan(r.value));
  EXPECT_EQ(pipeline::verdict_of(r), "not distinguishable");
}

TEST(GridConvergence, RichardsonRecoversOrderAndLimit) {
  // f(h) = 2 + 0.3 h^1.7, h = 1, 2, 4.
  auto f = [](double h) { return 2.0 + 0.3 * std::pow(h, 1.7); };
  const auto g = pipeline::richardson(f(1), f(2), f(4), 2.0);
  ASSERT_TRUE(g.monotone);
  EXPECT_NEAR(g.order, 1.7, 1e-12);
  EXPECT_NEAR(g.extrapolated, 2.0, 1e-12);
  // GCI = 1.25 |f1 - f2| / |f1| / (r^p - 1).
  EXPECT_NEAR(g.gci_fine, 1.25 * std::abs(f(1) - f(2)) / f(1) / (std::pow(2.0, 1.7) - 1.0), 1e-12);
}

TEST(GridConvergence, OscillatoryAndDivergentTriplesAreReportedNotForced) {
  const auto osc = pipeline::richardson(1.0, 1.1, 1.05, 2.0);
  EXPECT_FALSE(osc.monotone);
  EXPECT_TRUE(std::isnan(osc.extrapolated));
  EXPECT_NE(osc.note.find("oscillatory"), std::string::npos);
  const auto div = pipeline::richardson(1.0, 1.1, 1.15, 2.0);
  EXPECT_FALSE(div.monotone);
  EXPECT_NE(div.note.find("divergent"), std::string::npos);
}

TEST(ErrorMeasures, AreaBehindLineOfACutSquare) {
  const std::vector<scene::Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double b = std::numbers::pi / 4;  // line y = x
  const scene::Vec2 n{-std::sin(b), std::cos(b)};
  EXPECT_NEAR(pipeline::area_behind_line(sq, n), 0.5, 1e-15);
  // Clockwise input, same area; a square wholly ahead of the line, none.
  const std::vector<scene::Vec2> cw{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_NEAR(pipeline::area_behind_line(cw, n), 0.5, 1e-15);
  const std::vector<scene::Vec2> above{{0, 2}, {1, 2}, {1, 3}, {0, 3}};
  EXPECT_NEAR(pipeline::area_behind_line(above, n), 0.0, 1e-15);
  // Line y = x/2 cuts the unit square: the triangle below has area 1/4.
  const double b2 = std::atan(0.5);
  EXPECT_NEAR(pipeline::area_behind_line(sq, {-std::sin(b2), std::cos(b2)}), 0.25, 1e-15);
}

TEST(ErrorMeasures, PiecewiseL1OnAMeshCutByAKnownLine) {
  // Two unit cells side by side; the line y = x/2 cuts both. Cell 0 (x in
  // [0,1]) has 1/4 behind, cell 1 (x in [1,2]) has 3/4 behind.
  cfd::Mesh2D m;
  m.cell_polygons = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{1, 0}, {2, 0}, {2, 1}, {1, 1}}};
  m.cell_area = {1, 1};
  m.cell_centre = {{0.5, 0.5}, {1.5, 0.5}};
  const double b = std::atan(0.5), ahead = 1.4, behind = 3.0;
  // The exact cell averages give zero error.
  const std::vector<double> exact{ahead + 0.25 * (behind - ahead), ahead + 0.75 * (behind - ahead)};
  EXPECT_NEAR(pipeline::piecewise_l1(m, exact, b, ahead, behind, ahead), 0.0, 1e-14);
  // A field at the free-stream value everywhere: error = mean jump share.
  const std::vector<double> flat{ahead, ahead};
  const double want = (0.25 + 0.75) * (behind - ahead) / (2.0 * ahead);
  EXPECT_NEAR(pipeline::piecewise_l1(m, flat, b, ahead, behind, ahead), want, 1e-14);
}

}  // namespace

TEST(ReferenceGrid, CoarsestLevelFinerThanAllWithARatioTwoTriple) {
  scene::PipelineParams p;
  p.levels = {4, 2.8, 2, 1.4, 1};
  EXPECT_DOUBLE_EQ(pipeline::reference_grid_level(p), 0.7);  // with 1.4 and 2.8
  p.levels = {4, 2, 1};
  EXPECT_DOUBLE_EQ(pipeline::reference_grid_level(p), 0.5);  // with 1 and 2
  p.levels = {3, 1};
  EXPECT_DOUBLE_EQ(pipeline::reference_grid_level(p), 0.5);  // no triple: half the finest
  p.reference_level = 0.25;
  EXPECT_DOUBLE_EQ(pipeline::reference_grid_level(p), 0.25);
}

// The cost model against a measured grid: gmsh gave 1341 uniform cells at
// h = 0.03 on the wedge M3/10 domain (tests/data/wedge_verdict.yaml, level 2),
// and rhoCentralFoam 1472 steps to steady.
TEST(CostEstimate, UniformWedgeGridWithinTheStatedAccuracy) {
  auto s = scene::load_scene(std::string(SOURCE_DIR) + "/tests/data/wedge_verdict.yaml");
  const auto e = pipeline::estimate_run(s, "granular");
  const auto it = std::find_if(e.grids.begin(), e.grids.end(), [](const auto& g) { return g.name == "uniform_h2"; });
  ASSERT_NE(it, e.grids.end());
  constexpr double kModelAccuracy = 0.5;  // the model's stated +-50%
  EXPECT_NEAR(it->cells / 1341.0, 1.0, kModelAccuracy);
  EXPECT_NEAR(it->steps / 1472.0, 1.0, kModelAccuracy);
  EXPECT_GT(e.total_cpu_seconds, e.predictor_cpu_seconds);
  // Over budget: refused with the key named; --force-budget lets it run.
  s.pipeline.budget_cpu_seconds = 1.0;
  try {
    pipeline::check_budget(s, e, false);
    FAIL() << "over budget, not refused";
  } catch (const scene::InputError& err) {
    EXPECT_NE(std::string(err.what()).find("pipeline.budget_cpu_seconds"), std::string::npos) << err.what();
  }
  EXPECT_NO_THROW(pipeline::check_budget(s, e, true));
}

// Attached wedges are meshed with shock-aligned strips by default; the
// clustered estimate is meshgen's own (strips counted exactly) round the
// exact shock. Measured: the finest clustered grids of the three wedge case
// studies' runs at 7df6329, the scenes and strip layout of today
// (docs/case_studies.md top section; M4/15 and M5/20 at h_min 0.0046),
// where the isotropic band's model said 7941 for the first.
TEST(CostEstimate, StripGridsOfTheWedgeCaseStudiesWithinTheStatedAccuracy) {
  constexpr double kModelAccuracy = 0.5;  // the model's stated +-50%
  const std::vector<std::pair<std::string, double>> measured = {
      {"wedge_M3_10", 3098}, {"wedge_M4_15", 3136}, {"wedge_M5_20", 3662}};
  for (const auto& [name, cells] : measured) {
    SCOPED_TRACE(name);
    const auto s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    const auto e = pipeline::estimate_run(s, "granular", pipeline::band_scatter(s, "granular", ""));
    const auto it = std::find_if(e.grids.begin(), e.grids.end(),
                                 [](const auto& g) { return g.name == "clustered_h1"; });
    ASSERT_NE(it, e.grids.end());
    EXPECT_NEAR(it->cells / cells, 1.0, kModelAccuracy);
  }
}

// Every grid's cells are meshgen's own estimate; a bow shock's clustered
// grids are estimated round Billig's shock with the band a granular
// prediction carries (its stations' own intervals and the table's bow-shock
// scatter, passed here as the run passes it: disc 0.173, Apollo its shape's
// 0.073). Measured: the finest grids of the
// disc M4 (b8e69a3) and Apollo M5 (492233e) runs (docs/case_studies.md),
// where the isotropic-band formula said 12390 and 4595 clustered cells and
// 70677 uniform ones for the disc.
TEST(CostEstimate, BowShockGridsOfTheBluntCaseStudiesWithinTheStatedAccuracy) {
  constexpr double kModelAccuracy = 0.5;  // the model's stated +-50%
  struct Measured {
    std::string name;
    double clustered, uniform;
  };
  for (const Measured& m :
       {Measured{"disc_M4", 11562, 54205}, Measured{"apollo_M5", 3862, 13020}}) {
    SCOPED_TRACE(m.name);
    const auto s =
        scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + m.name + ".yaml");
    const auto e = pipeline::estimate_run(s, "granular", pipeline::band_scatter(s, "granular", ""));
    const auto cells = [&](const std::string& grid) {
      const auto it = std::find_if(e.grids.begin(), e.grids.end(),
                                   [&](const auto& g) { return g.name == grid; });
      EXPECT_NE(it, e.grids.end()) << grid;
      return it == e.grids.end() ? 0.0 : it->cells;
    };
    EXPECT_NEAR(cells("clustered_h1") / m.clustered, 1.0, kModelAccuracy);
    EXPECT_NEAR(cells("uniform_h1") / m.uniform, 1.0, kModelAccuracy);
  }
}

// A scene that leaves the cell sizes to the defaults gets sizes that fit its
// CPU budget (a default disc is estimated at tens of CPU hours); a scene that
// states either size keeps it and meets the budget check instead.
TEST(CostEstimate, DefaultSizesAreCoarsenedToTheBudget) {
  const std::string disc = "name: d\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 3}\n";
  scene::Scene s = scene::parse_scene(disc);
  ASSERT_TRUE(s.mesh.sizes_default);
  const scene::MeshParams before = s.mesh;
  ASSERT_GT(pipeline::estimate_run(s, "granular").total_cpu_seconds, s.pipeline.budget_cpu_seconds);
  const auto line = pipeline::fit_default_sizes_to_budget(s, "granular");
  ASSERT_TRUE(line.has_value());
  EXPECT_NE(line->find("pipeline.budget_cpu_seconds"), std::string::npos) << *line;
  EXPECT_LE(pipeline::estimate_run(s, "granular").total_cpu_seconds, s.pipeline.budget_cpu_seconds);
  // One factor for both sizes (to the 2 significant figures they are rounded to).
  constexpr double kRounding = 0.1;
  EXPECT_NEAR((s.mesh.h_max / s.mesh.h_min) / (before.h_max / before.h_min), 1.0, kRounding);
  // The finest that fits: 10% finer would not.
  scene::Scene finer = s;
  finer.mesh.h_min /= 1.1, finer.mesh.h_max /= 1.1;
  EXPECT_GT(pipeline::estimate_run(finer, "granular").total_cpu_seconds, s.pipeline.budget_cpu_seconds);

  scene::Scene given = scene::parse_scene(disc + "mesh: {h_min: 0.01}\n");
  EXPECT_FALSE(given.mesh.sizes_default);
  EXPECT_FALSE(pipeline::fit_default_sizes_to_budget(given, "granular").has_value());
  EXPECT_EQ(given.mesh.h_min, 0.01);
}

// The clustered grids' estimate follows meshgen's body rule: a wall at
// h_min (the default) costs more cells than one left at h_max.
TEST(CostEstimate, ClusteredEstimateCountsTheBodyLayers) {
  auto s = scene::load_scene(std::string(SOURCE_DIR) + "/tests/data/wedge_verdict.yaml");
  const auto clustered_cells = [&] {
    const auto e = pipeline::estimate_run(s, "correlation");
    const auto it = std::find_if(e.grids.begin(), e.grids.end(),
                                 [](const auto& g) { return g.name == "clustered-correlation_h2"; });
    EXPECT_NE(it, e.grids.end());
    return it == e.grids.end() ? 0.0 : it->cells;
  };
  const double wall_at_h_min = clustered_cells();
  s.mesh.h_body = s.mesh.h_max;
  EXPECT_GT(wall_at_h_min, clustered_cells());
}

// A CFD shock of the other kind than the flow's gets no value, with a note.
TEST(GridRuns, AShockOfTheOtherKindIsNoShockValue) {
  const scene::Scene wedge = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n");
  const scene::Scene detached_wedge = scene::parse_scene(
      "name: w\nbody: {kind: wedge, angle_deg: 30, length: 1}\nfreestream: {mach: 2}\n");
  EXPECT_FALSE(pipeline::foreign_shock_note(wedge, "attached").has_value());
  EXPECT_FALSE(pipeline::foreign_shock_note(wedge, "none").has_value());
  const auto note = pipeline::foreign_shock_note(wedge, "detached");
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("attached-shock flow"), std::string::npos) << *note;
  ASSERT_TRUE(pipeline::foreign_shock_note(detached_wedge, "attached").has_value());
  EXPECT_FALSE(pipeline::foreign_shock_note(detached_wedge, "detached").has_value());
}

// The granular stage's estimate follows its particle count (CPU ~ particles^1.5:
// measured 8.7x for 4x the particles on wedge M3/10) and its flow-through times, is capped by the
// stage's own granular.cpu_budget, and a count beyond what memory holds is refused by the estimate
// itself, before anything runs, naming the key.
TEST(CostEstimate, PredictorFollowsTheParticleCountAndRefusesAnAbsurdOne) {
  const std::string wedge =
      "name: w\nbody: {kind: wedge, angle_deg: 10, length: 1}\nfreestream: {mach: 3}\n";
  const double at_default =
      pipeline::estimate_run(scene::parse_scene(wedge), "granular").predictor_cpu_seconds;
  const double at_4x = pipeline::estimate_run(
                           scene::parse_scene(wedge + "granular: {particles: 36800}\n"), "granular")
                           .predictor_cpu_seconds;
  constexpr double kRelTolerance = 1e-9;
  EXPECT_NEAR(at_4x / at_default, 8.0, 8.0 * kRelTolerance);
  // ... and the flow-through times it simulates: a warm-up of 1.75 and the
  // averaging (kAttachedShockAveraging by default on an attached shock).
  const double at_4 =
      pipeline::estimate_run(scene::parse_scene(wedge + "granular: {averaging: 4}\n"), "granular")
          .predictor_cpu_seconds;
  EXPECT_NEAR(at_default / at_4, (1.75 + scene::kAttachedShockAveraging) / (1.75 + 4.0),
              kRelTolerance);
  const double capped =
      pipeline::estimate_run(
          scene::parse_scene(wedge + "granular: {particles: 36800, cpu_budget: 20}\n"), "granular")
          .predictor_cpu_seconds;
  EXPECT_EQ(capped, 20.0);
  EXPECT_EQ(pipeline::estimate_run(scene::parse_scene(wedge), "correlation").predictor_cpu_seconds,
            0.0);
  try {
    (void)pipeline::estimate_run(
        scene::parse_scene(wedge + "granular: {particles: 1000000000000}\n"), "granular");
    FAIL() << "1e12 particles estimated, not refused";
  } catch (const scene::InputError& err) {
    EXPECT_NE(std::string(err.what()).find("'particles'"), std::string::npos) << err.what();
  }
}

// Each predictor's clustered grids are estimated round the band it will
// carry. The correlation's is computed, so its estimate is meshgen's count of
// its own grid: measured by `pipeline predict --predictor correlation` and
// `meshgen SCENE --shock shock.csv` on the case studies' finest level
// (wedge M3/10 2553 cells, disc M4 5757, Apollo M5 2827), where the granular
// band's estimate said 3591, 8785 and 2928.
TEST(CostEstimate, CorrelationGridsAreEstimatedRoundItsOwnShock) {
  constexpr double kMeshgenEstimate = 0.05;  // meshgen's estimate against its own grids
  for (const auto& [name, cells] : std::vector<std::pair<std::string, double>>{
           {"wedge_M3_10", 2553}, {"disc_M4", 5757}, {"apollo_M5", 2827}}) {
    SCOPED_TRACE(name);
    const auto s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    const auto e = pipeline::estimate_run(s, "correlation");
    const auto it = std::find_if(e.grids.begin(), e.grids.end(), [](const auto& g) {
      return g.name == "clustered-correlation_h1";
    });
    ASSERT_NE(it, e.grids.end());
    EXPECT_NEAR(it->cells / cells, 1.0, kMeshgenEstimate);
  }
}

// The granular band follows the calibration the run will use: the table's
// out-of-sample scatter widens it; a scene that sets its restitution gets the
// run's own interval only, and fewer estimated cells.
TEST(CostEstimate, GranularBandFollowsTheCalibrationScatter) {
  for (const std::string name : {"wedge_M3_10", "disc_M4"}) {
    SCOPED_TRACE(name);
    const auto s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/" + name + ".yaml");
    const auto finest = [&](const pipeline::BandScatter& b) {
      const auto e = pipeline::estimate_run(s, "granular", b);
      const auto it = std::find_if(e.grids.begin(), e.grids.end(),
                                   [](const auto& g) { return g.name == "clustered_h1"; });
      EXPECT_NE(it, e.grids.end());
      return it == e.grids.end() ? 0.0 : it->cells;
    };
    const double own_only = finest({});
    const double with_table = finest({1.14, 0.173});  // the shipped table's wedge and bow-shock RMS
    EXPECT_GT(with_table, 1.2 * own_only);
    EXPECT_GT(finest({2.0 * 1.14, 2.0 * 0.173}), with_table);
  }
}
