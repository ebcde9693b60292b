// Calibration table: round trip, old-table interpolation, the fitted model; out-of-sample summary.
#include "pipeline/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pipeline/calibration_report.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

TEST(Calibration, RoundTripAndInterpolation) {
  pipeline::CalibrationTable t;
  t.entries = {{3, 10, 0.8, 0.02, 27.38, 27.5, 0.3}, {5, 20, 0.6, 0.03, 29.8, 29.9, 0.4}};
  const auto path = (test_support::scratch_root() / "calib_test.yaml").string();
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_EQ(back.entries.size(), 2u);
  EXPECT_DOUBLE_EQ(back.entries[1].restitution, 0.6);
  EXPECT_DOUBLE_EQ(*pipeline::interpolate_restitution(back, 3, 10), 0.8);  // exact match
  const double mid = *pipeline::interpolate_restitution(back, 4, 15);      // equidistant
  EXPECT_NEAR(mid, 0.7, 1e-12);
  EXPECT_FALSE(pipeline::interpolate_restitution(pipeline::CalibrationTable{}, 3, 10).has_value());
  // Blunt bodies (no angle): by Mach alone, M = 3 matches the first entry.
  EXPECT_DOUBLE_EQ(*pipeline::interpolate_restitution(back, 3, NAN), 0.8);
}

TEST(Calibration, AppliedOnlyWhenTheSceneLeavesRestitutionUnset) {
  pipeline::CalibrationTable t;
  t.entries = {{3, 10, 0.8, 0.02, 27.38, 27.5, 0.3}};
  const auto path = (test_support::scratch_root() / "calib_apply.yaml").string();
  pipeline::write_calibration(t, path);
  auto s = scene::parse_scene("body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const auto applied = pipeline::apply_calibration(s, path);
  EXPECT_NE(applied.note.find("from the calibration table"), std::string::npos);
  EXPECT_DOUBLE_EQ(s.granular.restitution, 0.8);
  // An old table's reruns are in sample: no out-of-sample scatter to widen a band with.
  EXPECT_TRUE(std::isnan(applied.angle_scatter_deg));
  auto given = scene::parse_scene(
      "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\ngranular: {restitution: 0.95}\n");
  EXPECT_EQ(pipeline::apply_calibration(given, path).note, "");
  EXPECT_DOUBLE_EQ(given.granular.restitution, 0.95);
}

TEST(Calibration, MalformedTableIsInputError) {
  const auto path = (test_support::scratch_root() / "calib_bad.yaml").string();
  scene::write_file_atomic(path, "entries: [{mach: 3, angle_deg: 10, restitution: 1.7}]\n");
  EXPECT_THROW(pipeline::read_calibration(path), scene::InputError);
  EXPECT_THROW(pipeline::read_calibration("/nonexistent/calib.yaml"), scene::InputError);
}

namespace {
// A fitted table: the Mach-and-angle model chosen, the Mach-only one beside it.
pipeline::CalibrationTable fitted_table() {
  pipeline::CalibrationTable t;
  pipeline::CalibrationEntry a;
  a.mach = 2.5;
  a.angle_deg = 8;
  a.restitution = 0.99;
  a.restitution_ci = 0.002;
  a.gas_angle_deg = 29.8;
  a.granular_angle_deg = 30.1;
  a.granular_angle_ci_deg = 0.6;
  a.loo_restitution = 0.9912345678;
  pipeline::CalibrationEntry b = a;
  b.mach = 6;
  b.angle_deg = 20;
  b.restitution = 0.96;
  b.gas_angle_deg = 28.26;
  b.granular_angle_deg = 29.66;  // out-of-sample errors +0.3 and +1.4 deg
  t.entries = {a, b};
  // Coefficients with all 17 digits significant (1/3 and friends).
  t.fits = {{pipeline::RestitutionModel::inverse_mach2,
             {0.95612345678901234, 1.0 / 3.0},
             0.0012345,
             0.0023456},
            {pipeline::RestitutionModel::inverse_mach2_angle,
             {0.9491, 2.0 / 7.0, 1.0 / 1300.0},
             0.001,
             0.002}};
  t.model = pipeline::RestitutionModel::inverse_mach2_angle;
  return t;
}
}  // namespace

TEST(Calibration, FittedTableRoundTripsAtFullPrecision) {
  auto t = fitted_table();
  t.cpu_seconds = 1094.5;
  const auto path = (test_support::scratch_root() / "calib_fit.yaml").string();
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.model.has_value());
  EXPECT_EQ(*back.model, pipeline::RestitutionModel::inverse_mach2_angle);
  ASSERT_EQ(back.fits.size(), 2u);
  for (std::size_t i = 0; i < t.fits.size(); ++i) {
    EXPECT_EQ(back.fits[i].model, t.fits[i].model);
    ASSERT_EQ(back.fits[i].coefficients.size(), t.fits[i].coefficients.size());
    for (std::size_t j = 0; j < t.fits[i].coefficients.size(); ++j)
      EXPECT_EQ(back.fits[i].coefficients[j], t.fits[i].coefficients[j]);  // bit for bit
    EXPECT_DOUBLE_EQ(back.fits[i].residual_sd, t.fits[i].residual_sd);
    EXPECT_DOUBLE_EQ(back.fits[i].loo_rms, t.fits[i].loo_rms);
  }
  EXPECT_DOUBLE_EQ(back.cpu_seconds,
                   1094.5);            // what the table cost, for the reports' amortised line
  ASSERT_EQ(back.entries.size(), 2u);  // the per-point entries are kept
  EXPECT_DOUBLE_EQ(back.entries[1].restitution, 0.96);
  EXPECT_NEAR(back.entries[0].loo_restitution, 0.991235, 1e-12);  // entries at 6 digits
  // The reread table evaluates exactly as the one written.
  EXPECT_EQ(*pipeline::interpolate_restitution(back, 4.0, 15.0),
            *pipeline::interpolate_restitution(t, 4.0, 15.0));
}

TEST(Calibration, FittedTableEvaluatesTheModel) {
  const auto t = fitted_table();
  // The chosen model, not the nearest entry: an entry's own point gives the fit's e.
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 6, 20),
              0.9491 + (2.0 / 7.0) / 36.0 + 20.0 / 1300.0, 1e-15);
  // Blunt bodies (NaN angle): the Mach-only model.
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 4, NAN), 0.95612345678901234 + 1.0 / 48.0,
              1e-15);
  // Below the training Mach numbers the fit would exceed the elastic limit.
  EXPECT_EQ(*pipeline::interpolate_restitution(t, 1.2, 8), 1.0);
}

TEST(Calibration, FittedTableAppliedToAScene) {
  const auto path = (test_support::scratch_root() / "calib_fit_apply.yaml").string();
  pipeline::write_calibration(fitted_table(), path);
  auto s = scene::parse_scene("body: {kind: wedge, angle_deg: 15}\nfreestream: {mach: 4}\n");
  const auto applied = pipeline::apply_calibration(s, path);
  EXPECT_NE(applied.note.find("from the calibration table"), std::string::npos);
  EXPECT_NEAR(s.granular.restitution, 0.9491 + (2.0 / 7.0) / 16.0 + 15.0 / 1300.0, 1e-6);
  // The RMS of the out-of-sample angle errors, +0.3 and +1.4 deg.
  const double rms = std::sqrt((0.3 * 0.3 + 1.4 * 1.4) / 2.0);
  EXPECT_NEAR(pipeline::out_of_sample_angle_rms_deg(fitted_table()), rms, 1e-9);
  // The band's scatter leaves out the left-out runs' own noise (both +-0.6 deg, sd 0.6 / 1.96),
  // which a new run's interval already holds.
  const double own = 0.6 / 1.96;
  EXPECT_NEAR(applied.angle_scatter_deg, std::sqrt(rms * rms - own * own), 1e-9);
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(fitted_table()), std::sqrt(rms * rms - own * own),
              1e-9);
  // A wedge's angle scatter is not a bow shock's: a disc gets none.
  auto disc = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
  EXPECT_TRUE(std::isnan(pipeline::apply_calibration(disc, path).angle_scatter_deg));
}

TEST(Calibration, TheBandsScatterIsTheTablesErrorWithoutTheRunsNoise) {
  auto t = fitted_table();
  // Left-out runs noisier than their errors: the table's own error is not seen, so zero.
  for (auto& e : t.entries) e.granular_angle_ci_deg = 4.0;
  EXPECT_EQ(pipeline::table_angle_scatter_deg(t), 0.0);
  // A run without an interval counts as noiseless, so the scatter errs wide.
  t.entries[0].granular_angle_ci_deg = NAN;
  t.entries[1].granular_angle_ci_deg = NAN;
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(t), pipeline::out_of_sample_angle_rms_deg(t),
              1e-12);
  // An old table (no leave-one-out runs) has none.
  for (auto& e : t.entries) e.loo_restitution = NAN;
  EXPECT_TRUE(std::isnan(pipeline::table_angle_scatter_deg(t)));
}

TEST(Calibration, OutsideTheTrainingMachRangeIsSaid) {
  // The training entries span Mach 2.5-6.
  const auto range = pipeline::training_mach_range(fitted_table());
  ASSERT_TRUE(range.has_value());
  EXPECT_DOUBLE_EQ(range->low, 2.5);
  EXPECT_DOUBLE_EQ(range->high, 6.0);
  EXPECT_FALSE(pipeline::training_mach_range(pipeline::CalibrationTable{}).has_value());
  const auto path = (test_support::scratch_root() / "calib_fit_range.yaml").string();
  pipeline::write_calibration(fitted_table(), path);
  // Inside (the ends included): no warning.
  for (const char* mach : {"2.5", "4", "6"}) {
    auto s = scene::parse_scene(
        std::string("body: {kind: disc, radius: 0.5}\nfreestream: {mach: ") + mach + "}\n");
    const auto applied = pipeline::apply_calibration(s, path);
    EXPECT_FALSE(applied.outside_training_mach) << mach;
    EXPECT_EQ(applied.note.find("WARNING"), std::string::npos) << mach;
  }
  // Above: extrapolated, said so.
  auto fast = scene::parse_scene("body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 7}\n");
  const auto above = pipeline::apply_calibration(fast, path);
  EXPECT_TRUE(above.outside_training_mach);
  EXPECT_NE(above.note.find("outside the table's training range 2.5-6"), std::string::npos);
  EXPECT_EQ(above.note.find("elastic limit"), std::string::npos);
  // Below: the Mach-only fit passes e = 1 and is held there.
  auto slow = scene::parse_scene("body: {kind: disc, radius: 1}\nfreestream: {mach: 1.5}\n");
  const auto below = pipeline::apply_calibration(slow, path);
  EXPECT_TRUE(below.outside_training_mach);
  EXPECT_DOUBLE_EQ(slow.granular.restitution, 1.0);
  EXPECT_NE(below.note.find("held at e = 1"), std::string::npos);
}

TEST(Calibration, OutsideTheTrainingDeflectionsIsSaid) {
  // The chosen model uses the wedge angle; the training entries span 8-20 deg.
  const auto range = pipeline::training_angle_range(fitted_table());
  ASSERT_TRUE(range.has_value());
  EXPECT_DOUBLE_EQ(range->low, 8.0);
  EXPECT_DOUBLE_EQ(range->high, 20.0);
  const auto path = (test_support::scratch_root() / "calib_fit_angles.yaml").string();
  pipeline::write_calibration(fitted_table(), path);
  auto inside = scene::parse_scene("body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 4}\n");
  EXPECT_EQ(pipeline::apply_calibration(inside, path).note.find("WARNING"), std::string::npos);
  auto thin = scene::parse_scene("body: {kind: wedge, angle_deg: 5}\nfreestream: {mach: 4}\n");
  const auto applied = pipeline::apply_calibration(thin, path);
  EXPECT_NE(
      applied.note.find("the 5 deg deflection lies outside the table's training range 8-20 deg"),
      std::string::npos)
      << applied.note;
  EXPECT_FALSE(applied.outside_training_mach);  // the Mach number is inside its range
}

TEST(Calibration, MalformedFitIsInputErrorNamingTheKey) {
  const auto path = (test_support::scratch_root() / "calib_bad_fit.yaml").string();
  const std::string entries = "entries: [{mach: 3, angle_deg: 10, restitution: 0.98}]\n";
  const auto message = [&](const std::string& text) -> std::string {
    scene::write_file_atomic(path, text);
    try {
      pipeline::read_calibration(path);
    } catch (const scene::InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(entries + "model: quadratic\nfits: []\n").find("'model'"), std::string::npos);
  EXPECT_NE(message(entries +
                    "model: inverse_mach2\nfits: [{model: inverse_mach2, coefficients: [0.9]}]\n")
                .find("'fits[0].coefficients'"),
            std::string::npos);
  EXPECT_NE(
      message(entries + "model: inverse_mach2_angle\n"
                        "fits: [{model: inverse_mach2_angle, coefficients: [0.9, 0.2, 0.001]}]\n")
          .find("inverse_mach2 fit"),
      std::string::npos);
  EXPECT_NE(message(entries + "fits: [{model: constant, coefficients: [0.9]}]\n").find("'model'"),
            std::string::npos);
  EXPECT_NE(message(entries + "model: constant\nfits: [{model: constant, coefficients: [0.9]}]\n"
                              "training_points: [[4, 10]]\n")
                .find("'training_points'"),
            std::string::npos);
  EXPECT_NE(message(entries + "model: quadratic\nfits: []\n").find(path),
            std::string::npos);     // names the file
  EXPECT_EQ(message(entries), "");  // an old table (entries only) is fine
}

TEST(Calibration, BluntBodiesKeepTheLawTheirBowBlockWasMeasuredUnder) {
  auto t = fitted_table();
  // Without a recorded law, blunt bodies take the table's Mach-only fit and a
  // new wedge fit drops the block (it was measured under the replaced fit).
  t.bow_shock = pipeline::BowShockScatter{};
  t.bow_shock->relative_rms = 0.17;
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 4, NAN), 0.95612345678901234 + 1.0 / 48.0,
              1e-15);
  EXPECT_FALSE(pipeline::bow_shock_kept_by_wedge_fit(t).has_value());

  // With one, blunt bodies take it whatever the wedge model, the block
  // survives a new wedge fit, and both round-trip bit for bit.
  const pipeline::RestitutionFit law{pipeline::RestitutionModel::log_mach,
                                     {1.0140391379828468, -1.0 / 36.0}, 0.003, 0.0028};
  t.bow_shock->restitution_law = law;
  const double blunt = 1.0140391379828468 - std::log(4.0) / 36.0;
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 4, NAN), blunt, 1e-15);
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 6, 20),
              0.9491 + (2.0 / 7.0) / 36.0 + 20.0 / 1300.0, 1e-15);  // wedges: the model
  const auto kept = pipeline::bow_shock_kept_by_wedge_fit(t);
  ASSERT_TRUE(kept.has_value());
  EXPECT_DOUBLE_EQ(kept->relative_rms, 0.17);

  const auto path = (test_support::scratch_root() / "calib_law.yaml").string();
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.bow_shock && back.bow_shock->restitution_law);
  EXPECT_EQ(back.bow_shock->restitution_law->model, pipeline::RestitutionModel::log_mach);
  EXPECT_EQ(back.bow_shock->restitution_law->coefficients, law.coefficients);
  EXPECT_EQ(*pipeline::interpolate_restitution(back, 4, NAN),
            *pipeline::interpolate_restitution(t, 4, NAN));

  // A law with a wedge angle cannot serve bodies without one.
  scene::write_file_atomic(
      path, "entries: [{mach: 3, angle_deg: 10, restitution: 0.98}]\n"
            "model: constant\nfits: [{model: constant, coefficients: [0.98]}]\n"
            "training_points: [[3, 10]]\n"
            "bow_shock: {relative_rms: 0.1, restitution_law: {model: inverse_mach2_angle, "
            "coefficients: [0.9, 0.2, 0.001]}}\n");
  try {
    pipeline::read_calibration(path);
    ADD_FAILURE() << "an angle law for blunt bodies was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'bow_shock.restitution_law'"), std::string::npos)
        << e.what();
  }
}

TEST(Calibration, AWedgeBeyondItsMaximumDeflectionTakesTheBluntLaw) {
  // The wedge fit matches attached angles; a detached wedge has none, so it
  // takes the blunt bodies' law like a disc, and the run says its standoff
  // is uncalibrated.
  auto t = fitted_table();
  t.bow_shock = pipeline::BowShockScatter{};
  t.bow_shock->relative_rms = 0.17;
  t.bow_shock->restitution_law = pipeline::RestitutionFit{
      pipeline::RestitutionModel::log_mach, {1.014, -0.028}, 0.003, 0.0028};
  const auto path = (test_support::scratch_root() / "calib_detached.yaml").string();
  pipeline::write_calibration(t, path);
  auto detached = scene::parse_scene("body: {kind: wedge, angle_deg: 36}\nfreestream: {mach: 3}\n");
  const auto applied = pipeline::apply_calibration(detached, path);
  EXPECT_NEAR(detached.granular.restitution, 1.014 - 0.028 * std::log(3.0), 1e-6);
  EXPECT_NE(applied.note.find("beyond the gas's maximum deflection"), std::string::npos)
      << applied.note;
  EXPECT_NE(applied.note.find("standoff's error is unmeasured"), std::string::npos);
  EXPECT_EQ(applied.note.find("deflection lies outside"), std::string::npos);  // no angle used
  // Just below the maximum deflection (34.07 deg at Mach 3) the wedge fit serves.
  auto attached = scene::parse_scene("body: {kind: wedge, angle_deg: 33}\nfreestream: {mach: 3}\n");
  pipeline::apply_calibration(attached, path);
  EXPECT_NEAR(attached.granular.restitution,
              std::min(*pipeline::interpolate_restitution(t, 3, 33), 1.0), 1e-6);
}

TEST(Calibration, OutOfSampleSummaryLeavesTrainingPointsOut) {
  nlohmann::json c = {
      {"model", "inverse_mach2"},
      {"candidates",
       {{{"model", "inverse_mach2"},
         {"formula", "e = c0 + c1/M^2"},
         {"coefficients", {0.95, 0.3}},
         {"residual_sd", 0.002},
         {"loo_rms", 0.003}}}},
      {"points",
       {{{"loo_angle_error_deg", 0.3}},
        {{"loo_angle_error_deg", -0.4}},
        {{"restitution", nullptr}}}},
      {"case_studies",
       {{{"angle_error_deg", 1.0}}, {{"angle_error_deg", 9.0}, {"in_sample", true}}}}};
  const auto s = pipeline::out_of_sample_summary(c);
  EXPECT_EQ(s["leave_one_out"]["n"], 2);
  EXPECT_NEAR(s["leave_one_out"]["rms_deg"].get<double>(), std::sqrt((0.09 + 0.16) / 2), 1e-12);
  EXPECT_NEAR(s["leave_one_out"]["max_abs_deg"].get<double>(), 0.4, 1e-12);
  EXPECT_EQ(s["case_studies"]["n"], 1);  // the in-sample case study does not count
  EXPECT_NEAR(s["case_studies"]["max_abs_deg"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(s["residual_sd_restitution"].get<double>(), 0.002, 1e-15);
}

// Training on measured crossings (pipeline parametric's JSON): the fit
// recovers e = c0 + c1/M^2 from exact points and never trains on a case study.
TEST(Calibration, FromPointsFitsAndLeavesTheCaseStudiesOut) {
  const auto dir = test_support::scratch_root() / "calib_from_points";
  std::filesystem::create_directories(dir);
  nlohmann::json j;
  j["crossings"] = nlohmann::json::array();
  for (const double m : {2.0, 2.5, 3.5, 4.5, 6.0})
    for (const double a : {8.0, 14.0})
      j["crossings"].push_back({{"mach", m},
                                {"angle_deg", a},
                                {"restitution", 0.95 + 0.2 / (m * m)},
                                {"restitution_ci", 0.002}});
  // A case study with a wild e: it must not enter the fit.
  j["crossings"].push_back(
      {{"mach", 3.0}, {"angle_deg", 10.0}, {"restitution", 0.5}, {"restitution_ci", 0.002}});
  scene::write_file_atomic((dir / "points.json").string(), j.dump());
  const auto r = pipeline::calibrate_from_points({(dir / "points.json").string()},
                                                 (dir / "table.yaml").string());
  EXPECT_EQ(r["points"].get<int>(), 10);
  EXPECT_EQ(r["case_studies_left_out"].get<int>(), 1);
  const auto t = pipeline::read_calibration((dir / "table.yaml").string());
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 4.0, 12.0), 0.95 + 0.2 / 16.0, 1e-9);

  // Refitting the shipped table keeps its bow block, which records the law its
  // blunt bodies ran at: their e does not move with the new wedge fit.
  const auto shipped = (dir / "shipped.yaml").string();
  std::filesystem::copy_file(pipeline::builtin_calibration_path(), shipped,
                             std::filesystem::copy_options::overwrite_existing);
  const auto before = pipeline::read_calibration(shipped);
  ASSERT_TRUE(before.bow_shock && before.bow_shock->restitution_law);
  const auto k = pipeline::calibrate_from_points({(dir / "points.json").string()}, shipped);
  EXPECT_TRUE(k["bow_shock_kept"].get<bool>());
  const auto after = pipeline::read_calibration(shipped);
  ASSERT_TRUE(after.bow_shock.has_value());
  EXPECT_EQ(after.bow_shock->shapes.size(), before.bow_shock->shapes.size());
  EXPECT_EQ(*pipeline::interpolate_restitution(after, 4.0, NAN),
            *pipeline::interpolate_restitution(before, 4.0, NAN));
  EXPECT_NEAR(*pipeline::interpolate_restitution(after, 4.0, 12.0), 0.95 + 0.2 / 16.0, 1e-9);
  // The measured angle scatter belonged to the replaced fit: dropped.
  EXPECT_TRUE(before.angle_scatter.has_value());
  EXPECT_FALSE(after.angle_scatter.has_value());

  scene::write_file_atomic((dir / "bad.json").string(), "{\"crossings\": 3}");
  EXPECT_THROW(pipeline::calibrate_from_points({(dir / "bad.json").string()}, ""),
               scene::InputError);
  EXPECT_THROW(pipeline::calibrate_from_points({(dir / "missing.json").string()}, ""),
               scene::InputError);
}

// A table extended by new training wedges: its own entries joined with the
// points of a calibrate run (its calibration.json), fitted as one set; the
// same wedge from two sources is refused, naming both.
TEST(Calibration, FromPointsJoinsATableWithNewTrainingWedges) {
  const auto dir = test_support::scratch_root() / "calib_from_points_join";
  std::filesystem::create_directories(dir);
  const auto law = [](double m) { return 0.95 + 0.2 / (m * m); };
  nlohmann::json low;
  low["crossings"] = nlohmann::json::array();
  for (const double m : {2.5, 3.5, 4.5})
    for (const double a : {8.0, 14.0})
      low["crossings"].push_back(
          {{"mach", m}, {"angle_deg", a}, {"restitution", law(m)}, {"restitution_ci", 0.002}});
  scene::write_file_atomic((dir / "low.json").string(), low.dump());
  const auto first = (dir / "first.yaml").string();
  pipeline::calibrate_from_points({(dir / "low.json").string()}, first);

  // calibrate's own output: `points`, one wedge without a crossing (null).
  nlohmann::json high;
  high["cpu_seconds"] = {{"total", 12.5}};
  high["points"] = nlohmann::json::array();
  for (const double a : {8.0, 14.0})
    high["points"].push_back({{"mach", 7.0},
                              {"angle_deg", a},
                              {"gas_angle_deg", 20.0},
                              {"restitution", law(7.0)},
                              {"restitution_ci", 0.002}});
  high["points"].push_back(
      {{"mach", 8.0}, {"angle_deg", 8.0}, {"restitution", nullptr}, {"restitution_ci", nullptr}});
  scene::write_file_atomic((dir / "high.json").string(), high.dump());

  const auto joined = (dir / "joined.yaml").string();
  const auto r = pipeline::calibrate_from_points({first, (dir / "high.json").string()}, joined);
  EXPECT_EQ(r["points"].get<int>(), 8);
  const auto t = pipeline::read_calibration(joined);
  ASSERT_EQ(t.entries.size(), 8u);
  EXPECT_DOUBLE_EQ(pipeline::training_mach_range(t)->high, 7.0);
  EXPECT_NEAR(*pipeline::interpolate_restitution(t, 6.0, 11.0), law(6.0), 1e-6);
  // The first table's out-of-sample checks belonged to its own fit.
  EXPECT_TRUE(std::isnan(t.entries.front().loo_restitution));

  try {
    pipeline::calibrate_from_points({first, (dir / "low.json").string()},
                                    (dir / "twice.yaml").string());
    ADD_FAILURE() << "a wedge given twice was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("also in " + first), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "twice.yaml"));

  // Extending needs a first source that is a table with a correction to keep.
  try {
    pipeline::calibrate_from_points({(dir / "high.json").string(), first},
                                    (dir / "kept.yaml").string(), true);
    ADD_FAILURE() << "--extend without a table first was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("high.json: key 'local_correction'"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "kept.yaml"));
}
