// A blunt shape's own restitution: the fit through its bodies' crossings,
// kept in the table, and taken by bodies of that shape only.
#include "pipeline/bow_shape_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kSource = SOURCE_DIR;
constexpr double kC0 = 0.96, kC1 = 0.05;

double exact_e(double mach) {
  return kC0 + kC1 / (mach * mach);
}

std::vector<pipeline::BowShapePoint> exact_points(std::initializer_list<double> machs) {
  std::vector<pipeline::BowShapePoint> pts;
  for (const double m : machs) {
    pipeline::BowShapePoint p;
    p.body = "disc_M" + std::to_string(static_cast<int>(m));
    p.mach = m;
    p.restitution = exact_e(m);
    p.restitution_ci = 0.002;
    pts.push_back(p);
  }
  return pts;
}

std::string table_with_disc_fit(const fs::path& d) {
  const std::string path = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", path, fs::copy_options::overwrite_existing);
  auto t = pipeline::read_calibration(path);
  auto fit = pipeline::fit_bow_shape("disc", exact_points({3.0, 5.0, 6.0}));
  fit->relative_rms = 0.0625;
  t.bow_shock.emplace();
  t.bow_shock->relative_rms = 0.171;
  t.bow_shock->bodies = {"disc_M3", "apollo_M7"};
  t.bow_shock->shapes.push_back(*fit);
  pipeline::write_calibration(t, path);
  return path;
}
}  // namespace

// Crossings on an exact e = c0 + c1/M^2: the fit and every left-out fit
// give it back.
TEST(BowShapeFit, RecoversAnExactLawAndItsLeftOutPredictions) {
  const auto fit = pipeline::fit_bow_shape("disc", exact_points({3.0, 5.0, 6.0}));
  ASSERT_TRUE(fit.has_value());
  ASSERT_EQ(fit->coefficients.size(), 2u);
  EXPECT_NEAR(fit->coefficients[0], kC0, 1e-10);
  EXPECT_NEAR(fit->coefficients[1], kC1, 1e-9);
  for (const auto& p : fit->points) EXPECT_NEAR(p.loo_restitution, exact_e(p.mach), 1e-9);
  EXPECT_NEAR(fit->evaluate(4.0), exact_e(4.0), 1e-10);
  EXPECT_EQ(fit->evaluate(0.5), pipeline::kMaxRestitution);  // held at the elastic limit
}

// Two bodies leave no left-out fit; one Mach number gives no slope.
TEST(BowShapeFit, TooFewBodiesOrOneMachNumberGiveNoFit) {
  EXPECT_FALSE(pipeline::fit_bow_shape("disc", exact_points({3.0, 6.0})).has_value());
  EXPECT_FALSE(pipeline::fit_bow_shape("disc", exact_points({4.0, 4.0, 4.0})).has_value());
}

// The table keeps a shape's fit to the digit; a disc takes it (and its
// scatter), Apollo and polygons keep the wedge e(M) and the pooled scatter.
TEST(BowShapeFit, TableKeepsItAndOnlyThatShapeTakesIt) {
  const fs::path d = test_support::scratch_root() / "shockgrain_bow_shape_table";
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string path = table_with_disc_fit(d);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.bow_shock.has_value());
  ASSERT_EQ(back.bow_shock->shapes.size(), 1u);
  const auto* disc_fit = back.bow_shock->shape("disc");
  ASSERT_NE(disc_fit, nullptr);
  EXPECT_EQ(back.bow_shock->shape("apollo"), nullptr);
  EXPECT_EQ(disc_fit->points.size(), 3u);
  EXPECT_EQ(disc_fit->relative_rms, 0.0625);
  EXPECT_NEAR(disc_fit->evaluate(4.0), exact_e(4.0), 1e-12);

  auto disc = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4.0}\n");
  const auto applied = pipeline::apply_calibration(disc, path);
  EXPECT_NEAR(disc.granular.restitution, exact_e(4.0), 1e-6);
  EXPECT_EQ(applied.bow_shock_relative_rms, 0.0625);
  EXPECT_NE(applied.note.find("disc shape"), std::string::npos) << applied.note;
  EXPECT_FALSE(applied.outside_training_mach);

  auto apollo =
      scene::parse_scene("body: {kind: apollo, diameter: 1.0}\nfreestream: {mach: 4.0}\n");
  const auto wedge_e = pipeline::interpolate_restitution(back, 4.0, scene::kNaN);
  EXPECT_EQ(pipeline::apply_calibration(apollo, path).bow_shock_relative_rms, 0.171);
  EXPECT_NEAR(apollo.granular.restitution, *wedge_e, 1e-6);

  // Outside the shape's own training range (Mach 3-6) the run says so, even
  // inside the wedge table's.
  auto slow = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 2.6}\n");
  EXPECT_TRUE(pipeline::apply_calibration(slow, path).outside_training_mach);

  // The tables are fitted with every impact at the table's e: a gas with
  // elastic slow impacts gets no e from them, and says which key to set.
  auto elastic = scene::parse_scene(
      "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4.0}\n"
      "granular: {elastic_impact_speed: 4}\n");
  try {
    pipeline::apply_calibration(elastic, path);
    FAIL() << "a table's e was applied to a gas it was not fitted on";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("granular.restitution"), std::string::npos) << e.what();
  }
  elastic.granular.restitution_given = true;
  EXPECT_NO_THROW(pipeline::apply_calibration(elastic, path));
}

// A shape fit with fewer than three bodies is a malformed table.
TEST(BowShapeFit, TableWithATwoBodyShapeIsRefused) {
  const fs::path d = test_support::scratch_root() / "shockgrain_bow_shape_bad";
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string path = table_with_disc_fit(d);
  std::string text = scene::read_file(path);
  const auto at = text.find("- {body: disc_M6");
  ASSERT_NE(at, std::string::npos) << text;
  const auto line = text.rfind('\n', at);
  text.erase(line, text.find('\n', at) - line);
  scene::write_file_atomic(path, text);
  try {
    pipeline::read_calibration(path);
    FAIL() << "a two-body shape fit was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bow_shock.shapes[0].points"), std::string::npos)
        << e.what();
  }
}

// The gas's standoff is the uniform grid's own stagnation-line reading where
// it stopped (history.csv), in body lengths from the nose: a disc of radius
// 0.5 (the body length) with its nose at x = -0.5 and the shock read at
// x = -0.775 at the last written time stands 0.55 radii off.
TEST(BowShapeFit, GasStandoffIsTheFinestUniformGridsStagnationLineReading) {
  const fs::path d = test_support::scratch_root() / "shockgrain_bow_gas_standoff";
  fs::remove_all(d);
  fs::create_directories(d / "cfd/uniform_h1");
  fs::create_directories(d / "cfd/uniform_h2");
  scene::write_file_atomic((d / "scene.resolved.yaml").string(),
                           "name: disc_M3.3\nbody: {kind: disc, radius: 0.5}\n"
                           "freestream: {mach: 3.3}\n");
  scene::write_file_atomic((d / "summary.json").string(),
                           R"({"prediction": {"predictor": "granular", "cpu_seconds": 5},
          "runs": [{"family": "uniform", "level": 2, "steady_state_reached": true,
                    "cpu_seconds": 10, "mesh_cpu_seconds": 1},
                   {"family": "uniform", "level": 1, "steady_state_reached": true,
                    "cpu_seconds": 40, "mesh_cpu_seconds": 2}]})");
  scene::write_file_atomic((d / "cfd/uniform_h2/history.csv").string(),
                           "time,shock_x\n1,-0.70\n2,-0.80\n");
  scene::write_file_atomic((d / "cfd/uniform_h1/history.csv").string(),
                           "time,shock_x\n1,-0.70\n2,-0.775\n3,nan\n");
  const auto run = pipeline::bow_training_run(d.string());
  EXPECT_NEAR(pipeline::gas_standoff(run), 0.55, 1e-12);
  EXPECT_DOUBLE_EQ(run.grid_cpu_seconds, 42.0);

  // A reading behind the nose is no standoff: refused, naming the file.
  scene::write_file_atomic((d / "cfd/uniform_h1/history.csv").string(), "time,shock_x\n1,-0.4\n");
  try {
    pipeline::gas_standoff(run);
    FAIL() << "a shock behind the nose was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uniform_h1/history.csv"), std::string::npos) << e.what();
  }
}
