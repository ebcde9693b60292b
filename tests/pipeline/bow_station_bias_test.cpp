// A blunt shape's station bias: the fold of the granular bow shock against
// the gas's, fitted over bodies, judged by leaving each out, stored in the
// table, given to the shape's bodies and taken out of their stations.
#include "pipeline/bow_station_bias.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kSource = SOURCE_DIR;

fs::path fresh(const std::string& name) {
  return test_support::fresh_dir("shockgrain_bias_" + name);
}

// A body whose stations (inclinations 0-85 deg) and standoff miss the gas's
// by exactly r = b0 + b1 s + b2 / M^2 + q s^2.
pipeline::StationErrors folded_body(const std::string& name, double mach, double b0, double b1,
                                    double b2, double q = 0) {
  pipeline::StationErrors e;
  e.body = name;
  e.mach = mach;
  e.shape = "disc";
  double ss = 0, sum = 0;
  for (int k = 0; k <= 17; ++k) {
    const double inc = 5.0 * k;
    const double s = inc / 90.0;
    const double r = b0 + b1 * s + b2 / (mach * mach) + q * s * s;
    e.inclination_deg.push_back(inc);
    e.relative.push_back(r);
    ss += r * r;
    sum += r;
  }
  e.rms = std::sqrt(ss / 18.0);
  e.mean = sum / 18.0;
  e.standoff_relative = b0 + b2 / (mach * mach);
  return e;
}

pipeline::BowStationBias disc_bias() {
  pipeline::BowStationBias b;
  b.shape = "disc";
  b.model = "inclination_mach";
  b.coefficients = {0.1, -0.4, 1.5};
  b.relative_rms = 0.07;
  b.uncorrected_rms = 0.12;
  b.max_inclination_deg = 87.5;
  b.mach_low = 3;
  b.mach_high = 6;
  b.bodies.push_back({"disc_M3", 3, 33, 1, 0.05, 0.11, 0.3, -0.1, 0.1, -0.05});
  return b;
}
}  // namespace

TEST(StationBias, InclinationIsFromTheUpstreamDirection) {
  EXPECT_NEAR(pipeline::inclination_deg({-1.0, 0.0}), 0.0, 1e-12);
  EXPECT_NEAR(pipeline::inclination_deg({0.0, 1.0}), 90.0, 1e-12);
  EXPECT_NEAR(pipeline::inclination_deg({0.0, -1.0}), 90.0, 1e-12);  // the lower branch alike
  EXPECT_NEAR(pipeline::inclination_deg({-std::sqrt(0.5), std::sqrt(0.5)}), 45.0, 1e-12);
  EXPECT_TRUE(std::isnan(pipeline::inclination_deg({std::nan(""), 0.0})));
}

TEST(StationBias, AFoldThatMovesWithMachIsFoundAndLeftOutBodiesAreCorrected) {
  const std::vector<pipeline::StationErrors> bodies{folded_body("a", 3, 0.1, -0.4, 1.5),
                                                    folded_body("b", 5, 0.1, -0.4, 1.5),
                                                    folded_body("c", 6, 0.1, -0.4, 1.5)};
  const auto fit = pipeline::fit_station_bias("disc", bodies);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->model, "inclination_mach");
  ASSERT_EQ(fit->coefficients.size(), 3u);
  EXPECT_NEAR(fit->coefficients[0], 0.1, 1e-9);
  EXPECT_NEAR(fit->coefficients[1], -0.4, 1e-9);
  EXPECT_NEAR(fit->coefficients[2], 1.5, 1e-9);
  EXPECT_NEAR(fit->relative_rms, 0.0, 1e-9);  // each body's left-out fit is exact
  EXPECT_GT(fit->uncorrected_rms, 0.1);
  ASSERT_EQ(fit->bodies.size(), 3u);
  for (const auto& b : fit->bodies) EXPECT_NEAR(b.loo_standoff, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(fit->mach_low, 3.0);
  EXPECT_DOUBLE_EQ(fit->mach_high, 6.0);
  EXPECT_DOUBLE_EQ(fit->max_inclination_deg, 85.0);
}

// The standoff, a parabola's vertex through the near-axis stations, can miss
// by more than the fold at s = 0 says: then it takes its own term q(M), chosen
// like the fold by leaving each body out; where it misses by the fold alone,
// none.
pipeline::StationErrors with_standoff_term(pipeline::StationErrors e, double q) {
  e.standoff_relative = (1.0 + e.standoff_relative) * (1.0 + q) - 1.0;
  return e;
}

TEST(StationBias, AStandoffThatMissesBeyondItsStationsTakesItsOwnTerm) {
  const auto bodies = [](auto q) {
    std::vector<pipeline::StationErrors> out;
    for (const double m : {3.0, 4.0, 5.0, 6.0})
      out.push_back(
          with_standoff_term(folded_body("m" + std::to_string(m), m, 0.1, -0.4, 1.5), q(m)));
    return out;
  };
  const auto none = pipeline::fit_station_bias("disc", bodies([](double) { return 0.0; }));
  ASSERT_TRUE(none.has_value());
  EXPECT_EQ(none->standoff_model, "none");
  EXPECT_TRUE(none->standoff_coefficients.empty());
  EXPECT_EQ(none->standoff_left_out_rms.size(), 3u);  // every candidate judged

  const auto constant = pipeline::fit_station_bias("disc", bodies([](double) { return 0.05; }));
  ASSERT_TRUE(constant.has_value());
  EXPECT_EQ(constant->model, "inclination_mach");  // the stations' fold is untouched
  EXPECT_EQ(constant->standoff_model, "constant");
  ASSERT_EQ(constant->standoff_coefficients.size(), 1u);
  EXPECT_NEAR(constant->standoff_coefficients[0], 0.05, 1e-9);
  for (const auto& b : constant->bodies) EXPECT_NEAR(b.loo_standoff, 0.0, 1e-9);

  const auto mach =
      pipeline::fit_station_bias("disc", bodies([](double m) { return -0.02 + 1.2 / (m * m); }));
  ASSERT_TRUE(mach.has_value());
  EXPECT_EQ(mach->standoff_model, "inverse_mach2");
  ASSERT_EQ(mach->standoff_coefficients.size(), 2u);
  EXPECT_NEAR(mach->standoff_coefficients[0], -0.02, 1e-9);
  EXPECT_NEAR(mach->standoff_coefficients[1], 1.2, 1e-9);
  // The standoff is divided by both: the fold at the nose and its own term,
  // each held at the training Mach ends.
  const double r0 = 0.1 + 1.5 / 16.0, q = -0.02 + 1.2 / 16.0;
  EXPECT_NEAR(pipeline::unbiased_standoff_factor(*mach, 4.0), 1.0 / ((1.0 + r0) * (1.0 + q)), 1e-9);
  EXPECT_DOUBLE_EQ(mach->standoff_error(9.0), mach->standoff_error(6.0));
}

TEST(StationBias, AFoldThatFlattensAtTheNoseTakesTheQuadraticModel) {
  // Flat near the stagnation line, falling toward the wings: a straight
  // line in s would stand the nose wrong; the quadratic is exact there.
  const std::vector<pipeline::StationErrors> bodies{
      folded_body("a", 3, 0.1, 0.0, 1.5, -0.3), folded_body("b", 4, 0.1, 0.0, 1.5, -0.3),
      folded_body("c", 5, 0.1, 0.0, 1.5, -0.3), folded_body("d", 6, 0.1, 0.0, 1.5, -0.3)};
  const auto fit = pipeline::fit_station_bias("disc", bodies);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->model, "inclination2_mach");
  ASSERT_EQ(fit->coefficients.size(), 4u);
  EXPECT_NEAR(fit->coefficients[0], 0.1, 1e-9);
  EXPECT_NEAR(fit->coefficients[1], 0.0, 1e-9);
  EXPECT_NEAR(fit->coefficients[2], -0.3, 1e-9);
  EXPECT_NEAR(fit->coefficients[3], 1.5, 1e-9);
  EXPECT_NEAR(fit->relative_rms, 0.0, 1e-9);
  for (const auto& b : fit->bodies) EXPECT_NEAR(b.loo_standoff, 0.0, 1e-9);
  EXPECT_EQ(pipeline::station_bias_coefficients("inclination2_mach"), 4u);
  EXPECT_EQ(pipeline::station_bias_coefficients("quartic"), 0u);
}

TEST(StationBias, RunsOfOneBodyArePooledAsThatBody) {
  // Two seeds of body b, one high and one low by the same amount: one body
  // whose standoff error is their mean; three bodies, so the fit exists, and
  // two seeds of a and b alone are still two bodies, so it does not.
  const auto a = folded_body("a", 3, 0.1, -0.4, 1.5);
  auto b_high = folded_body("b", 5, 0.12, -0.4, 1.5);
  auto b_low = folded_body("b", 5, 0.08, -0.4, 1.5);
  const auto c = folded_body("c", 6, 0.1, -0.4, 1.5);
  const auto fit = pipeline::fit_station_bias("disc", {a, b_high, c, b_low});
  ASSERT_TRUE(fit.has_value());
  ASSERT_EQ(fit->bodies.size(), 3u);
  EXPECT_EQ(fit->bodies[1].body, "b");
  EXPECT_EQ(fit->bodies[1].runs, 2);
  EXPECT_EQ(fit->bodies[1].stations, 36);
  EXPECT_NEAR(fit->bodies[1].standoff, 0.1 + 1.5 / 25.0, 1e-12);
  EXPECT_NEAR(fit->coefficients[0], 0.1, 1e-9);  // the seeds' spread averages out
  EXPECT_FALSE(pipeline::fit_station_bias("disc", {a, b_high, b_low}).has_value());
}

TEST(StationBias, AFoldThatDoesNotMoveWithMachKeepsTheSimplerModel) {
  const std::vector<pipeline::StationErrors> bodies{folded_body("a", 3, 0.2, -0.4, 0),
                                                    folded_body("b", 5, 0.2, -0.4, 0),
                                                    folded_body("c", 6, 0.2, -0.4, 0)};
  const auto fit = pipeline::fit_station_bias("disc", bodies);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->model, "inclination");
  EXPECT_NEAR(fit->coefficients[0], 0.2, 1e-9);
  EXPECT_NEAR(fit->coefficients[1], -0.4, 1e-9);
}

TEST(StationBias, TooFewBodiesOrNoStandoffOrNegativeDistancesGiveNoFit) {
  const auto a = folded_body("a", 3, 0.1, -0.4, 1.5);
  const auto b = folded_body("b", 5, 0.1, -0.4, 1.5);
  auto c = folded_body("c", 6, 0.1, -0.4, 1.5);
  EXPECT_FALSE(pipeline::fit_station_bias("disc", {a, b}).has_value());
  c.standoff_relative = std::nan("");
  EXPECT_FALSE(pipeline::fit_station_bias("disc", {a, b, c}).has_value());
  // A fold that would put the shock behind the body (1 + r <= 0.5) is refused.
  EXPECT_FALSE(pipeline::fit_station_bias(
                   "disc", {folded_body("a", 3, 0, -0.9, 0), folded_body("b", 5, 0, -0.9, 0),
                            folded_body("c", 6, 0, -0.9, 0)})
                   .has_value());
}

TEST(StationBias, StationsMoveAlongTheirNormalsAndTheModelIsHeldOutsideItsRange) {
  const auto b = disc_bias();
  scene::ShockCsvRow nose;
  nose.surface = {-0.5, 0.0};
  nose.normal = {-1.0, 0.0};
  nose.distance = 0.3;
  nose.ci = 0.01;
  nose.shock = {-0.8, 0.0};
  nose.accepted = true;
  scene::ShockCsvRow top = nose;
  top.surface = {0.0, 0.5};
  top.normal = {0.0, 1.0};
  top.shock = {0.0, 0.8};
  const auto out = pipeline::unbiased_stations({nose, top}, b, 4.0);
  const double r0 = 0.1 + 1.5 / 16.0;
  EXPECT_NEAR(out[0].distance, 0.3 / (1.0 + r0), 1e-12);
  EXPECT_NEAR(out[0].ci, 0.01 / (1.0 + r0), 1e-12);
  EXPECT_NEAR(out[0].shock.x, -0.5 - 0.3 / (1.0 + r0), 1e-12);
  EXPECT_NEAR(out[0].shock.y, 0.0, 1e-12);
  // The top station lies beyond the training stations (87.5 deg): held there.
  const double r90 = 0.1 - 0.4 * 87.5 / 90.0 + 1.5 / 16.0;
  EXPECT_NEAR(out[1].distance, 0.3 / (1.0 + r90), 1e-12);
  EXPECT_NEAR(out[1].shock.y, 0.5 + 0.3 / (1.0 + r90), 1e-12);
  EXPECT_NEAR(pipeline::unbiased_standoff_factor(b, 4.0), 1.0 / (1.0 + r0), 1e-12);
  // Beyond the training Mach numbers the model is held at the nearest end.
  EXPECT_DOUBLE_EQ(b.relative_error(10.0, 0.0), b.relative_error(6.0, 0.0));
  EXPECT_DOUBLE_EQ(b.relative_error(2.0, 30.0), b.relative_error(3.0, 30.0));
}

TEST(StationBias, TheTableKeepsItAndTheShapesBodiesGetIt) {
  const fs::path d = fresh("table");
  const std::string path = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", path);
  auto t = pipeline::read_calibration(path);
  ASSERT_TRUE(t.bow_shock.has_value());
  t.bow_shock->station_biases = {disc_bias()};
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  const pipeline::BowStationBias* b = back.bow_shock->station_bias("disc");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->model, "inclination_mach");
  EXPECT_EQ(b->coefficients, disc_bias().coefficients);
  EXPECT_EQ(b->relative_rms, 0.07);
  ASSERT_EQ(b->bodies.size(), 1u);
  EXPECT_EQ(b->bodies[0].loo_standoff, -0.05);
  EXPECT_NEAR(pipeline::left_out_standoff_rms(*b), 0.05, 1e-15);
  EXPECT_EQ(b->standoff_model, "none");  // a bias written without a standoff term

  auto termed = disc_bias();
  termed.standoff_model = "inverse_mach2";
  termed.standoff_coefficients = {-0.02, 0.3};
  termed.standoff_left_out_rms = {{"none", 0.04}, {"constant", 0.035}, {"inverse_mach2", 0.03}};
  t.bow_shock->station_biases = {termed};
  pipeline::write_calibration(t, path);
  const auto termed_table = pipeline::read_calibration(path);
  const auto* termed_back = termed_table.bow_shock->station_bias("disc");
  ASSERT_NE(termed_back, nullptr);
  EXPECT_EQ(termed_back->standoff_model, "inverse_mach2");
  EXPECT_EQ(termed_back->standoff_coefficients, termed.standoff_coefficients);
  EXPECT_EQ(termed_back->standoff_left_out_rms, termed.standoff_left_out_rms);
  t.bow_shock->station_biases = {disc_bias()};
  pipeline::write_calibration(t, path);

  auto disc = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
  const auto applied = pipeline::apply_calibration(disc, path);
  ASSERT_TRUE(applied.station_bias.has_value());
  EXPECT_EQ(applied.bow_shock_relative_rms, 0.07);  // the corrected stations' scatter
  EXPECT_NE(applied.note.find("station bias"), std::string::npos);
  EXPECT_FALSE(applied.outside_training_mach);
  auto far = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 8}\n");
  EXPECT_TRUE(pipeline::apply_calibration(far, path).outside_training_mach);
  // Apollo has its own e: no bias; a wedge has none either.
  auto apollo = scene::parse_scene("body: {kind: apollo, diameter: 1}\nfreestream: {mach: 5}\n");
  EXPECT_FALSE(pipeline::apply_calibration(apollo, path).station_bias.has_value());
  auto wedge = scene::parse_scene("body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 3.5}\n");
  EXPECT_FALSE(pipeline::apply_calibration(wedge, path).station_bias.has_value());
}

TEST(StationBias, BadBlocksAreInputErrorsNamingTheKey) {
  const fs::path d = fresh("bad");
  const std::string path = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", path);
  auto t = pipeline::read_calibration(path);
  auto bad = disc_bias();
  bad.model = "quadratic";
  t.bow_shock->station_biases = {bad};
  pipeline::write_calibration(t, path);
  try {
    pipeline::read_calibration(path);
    FAIL() << "an unknown model was read";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bow_shock.station_bias[0].model"), std::string::npos);
  }
  // A standoff term of an unknown model, or with the wrong coefficient count.
  const auto expect_key = [&](const pipeline::BowStationBias& b, const std::string& key) {
    t.bow_shock->station_biases = {b};
    pipeline::write_calibration(t, path);
    try {
      pipeline::read_calibration(path);
      ADD_FAILURE() << "read a bad " << key;
    } catch (const scene::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  auto cubic = disc_bias();
  cubic.standoff_model = "cubic";
  expect_key(cubic, "bow_shock.station_bias[0].standoff_model");
  auto short_term = disc_bias();
  short_term.standoff_model = "inverse_mach2";
  short_term.standoff_coefficients = {0.1};
  expect_key(short_term, "bow_shock.station_bias[0].standoff_coefficients");
  // A shape with its own e fit runs its bodies elsewhere than at the law.
  auto own = disc_bias();
  own.shape = "apollo";
  t.bow_shock->station_biases = {own};
  pipeline::write_calibration(t, path);
  EXPECT_THROW(pipeline::read_calibration(path), scene::InputError);
}

TEST(StationBias, CalibrateRefusesATableWithoutABluntLawAndLeavesItAlone) {
  const fs::path d = fresh("nolaw");
  const std::string path = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", path);
  auto t = pipeline::read_calibration(path);
  t.bow_shock->restitution_law.reset();
  pipeline::write_calibration(t, path);
  const std::string before = scene::read_file(path);
  EXPECT_THROW(pipeline::calibrate_station_biases({d.string()}, path), scene::InputError);
  EXPECT_EQ(scene::read_file(path), before);
  // A directory that is no run: named, the table untouched.
  t.bow_shock->restitution_law =
      pipeline::read_calibration(kSource + "/pipeline/calibration.yaml").bow_shock->restitution_law;
  pipeline::write_calibration(t, path);
  const std::string with_law = scene::read_file(path);
  EXPECT_THROW(pipeline::calibrate_station_biases({(d / "missing").string()}, path),
               scene::InputError);
  EXPECT_EQ(scene::read_file(path), with_law);
}
