// Restitution models: the fit, the leave-one-out choice, and the training set.
#include "pipeline/restitution_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/calibration_training.hpp"
#include "pipeline/studies.hpp"

namespace {
using pipeline::RestitutionModel;
using pipeline::RestitutionPoint;

// Exact arithmetic on well-conditioned synthetic data leaves rounding only.
constexpr double kCoefficientTolerance = 1e-10;

// The default training grid with e from a known law plus `noise(i)`.
template <class Law, class Noise>
std::vector<RestitutionPoint> synthetic(Law law, Noise noise) {
  std::vector<RestitutionPoint> pts;
  int i = 0;
  for (const double m : {2.5, 3.5, 4.5, 6.0})
    for (const double a : {8.0, 14.0, 20.0}) {
      pts.push_back({m, a, law(m, a) + noise(i), 0.002});
      ++i;
    }
  return pts;
}
}  // namespace

TEST(RestitutionFit, RecoversKnownCoefficients) {
  const auto mach_only =
      synthetic([](double m, double) { return 0.956 + 0.25 / (m * m); }, [](int) { return 0.0; });
  const auto f = pipeline::fit_restitution(mach_only, RestitutionModel::inverse_mach2);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->coefficients[0], 0.956, kCoefficientTolerance);
  EXPECT_NEAR(f->coefficients[1], 0.25, kCoefficientTolerance);
  EXPECT_NEAR(f->residual_sd, 0.0, kCoefficientTolerance);

  const auto with_angle =
      synthetic([](double m, double a) { return 0.95 + 0.2 / (m * m) + 0.0007 * a; },
                [](int) { return 0.0; });
  const auto g = pipeline::fit_restitution(with_angle, RestitutionModel::inverse_mach2_angle);
  ASSERT_TRUE(g.has_value());
  EXPECT_NEAR(g->coefficients[0], 0.95, kCoefficientTolerance);
  EXPECT_NEAR(g->coefficients[1], 0.2, kCoefficientTolerance);
  EXPECT_NEAR(g->coefficients[2], 0.0007, kCoefficientTolerance);
  EXPECT_NEAR(g->evaluate(5.0, 20.0), 0.95 + 0.2 / 25.0 + 0.014, kCoefficientTolerance);
}

TEST(RestitutionFit, WeightsFollowTheCrossingInterval) {
  // Two points at M = 3: a precise one and a vague one. The constant model's
  // value must sit near the precise one.
  const std::vector<RestitutionPoint> pts{{3, 10, 0.98, 0.001}, {3, 14, 0.96, 0.01}};
  const auto f = pipeline::fit_restitution(pts, RestitutionModel::constant);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->coefficients[0], (0.98 * 1e6 + 0.96 * 1e4) / (1e6 + 1e4), kCoefficientTolerance);
}

TEST(RestitutionFit, SingularDesignIsRefused) {
  // Every point at one Mach number: 1 and 1/M^2 are the same column.
  const std::vector<RestitutionPoint> pts{
      {3, 8, 0.98, 0.002}, {3, 14, 0.97, 0.002}, {3, 20, 0.96, 0.002}};
  EXPECT_FALSE(pipeline::fit_restitution(pts, RestitutionModel::inverse_mach2).has_value());
  EXPECT_FALSE(
      pipeline::fit_restitution(std::vector<RestitutionPoint>{}, RestitutionModel::constant)
          .has_value());
}

TEST(RestitutionFit, LeaveOneOutPicksTheRightModel) {
  // Noise of 0.002 that alternates in sign along Mach and is independent of
  // the angle: the angle term only fits noise and loses out of sample.
  const auto noise = [](int i) {
    return (i % 2 == 0 ? 1.0 : -1.0) * 0.002 * ((i % 3) == 1 ? 0.5 : 1.0);
  };
  const auto mach_only = synthetic([](double m, double) { return 0.956 + 0.25 / (m * m); }, noise);
  const auto c1 = pipeline::choose_restitution_model(mach_only);
  ASSERT_TRUE(c1.has_value());
  EXPECT_EQ(c1->fit().model, RestitutionModel::inverse_mach2);
  EXPECT_EQ(c1->candidates.size(), std::size(pipeline::kRestitutionModels));

  // A real angle dependence (0.02 over 8-20 deg) well above the same noise.
  const auto with_angle =
      synthetic([](double m, double a) { return 0.94 + 0.25 / (m * m) + 0.0017 * a; }, noise);
  const auto c2 = pipeline::choose_restitution_model(with_angle);
  ASSERT_TRUE(c2.has_value());
  EXPECT_EQ(c2->fit().model, RestitutionModel::inverse_mach2_angle);

  // Exact Mach-only data: both adequate models score ~0; the simpler wins.
  const auto exact =
      synthetic([](double m, double) { return 0.956 + 0.25 / (m * m); }, [](int) { return 0.0; });
  EXPECT_EQ(pipeline::choose_restitution_model(exact)->fit().model,
            RestitutionModel::inverse_mach2);
}

TEST(RestitutionFit, LogMachLawIsRecoveredAndChosen) {
  // e still falling at high Mach number, as ln M does and 1/M^2 does not.
  const auto law = [](double m, double) { return 1.014 - 0.0277 * std::log(m); };
  const auto exact = synthetic(law, [](int) { return 0.0; });
  const auto f = pipeline::fit_restitution(exact, RestitutionModel::log_mach);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->coefficients[0], 1.014, kCoefficientTolerance);
  EXPECT_NEAR(f->coefficients[1], -0.0277, kCoefficientTolerance);
  EXPECT_EQ(pipeline::model_key(RestitutionModel::log_mach), "log_mach");
  EXPECT_EQ(pipeline::model_from_key("log_mach"), RestitutionModel::log_mach);
  EXPECT_FALSE(pipeline::uses_angle(RestitutionModel::log_mach));

  // With noise a fifth of the 1/M^2 model's misfit at the Mach ends (0.003), ln M
  // wins out of sample.
  const auto noise = [](int i) { return (i % 2 == 0 ? 1.0 : -1.0) * 0.0005; };
  const auto c = pipeline::choose_restitution_model(synthetic(law, noise));
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->fit().model, RestitutionModel::log_mach);
}

TEST(RestitutionFit, AnAngleTermThatLevelsOffIsRecoveredAndChosen) {
  // e falling with ln M and with a deflection term that levels off (1/theta),
  // as the training crossings do, with noise of 0.0003: the 1/theta model
  // wins out of sample over the linear angle terms.
  const auto law = [](double m, double a) { return 1.01 - 0.03 * std::log(m) + 0.05 / a; };
  const auto exact = synthetic(law, [](int) { return 0.0; });
  const auto f = pipeline::fit_restitution(exact, RestitutionModel::log_mach_inverse_angle);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->coefficients[0], 1.01, kCoefficientTolerance);
  EXPECT_NEAR(f->coefficients[1], -0.03, kCoefficientTolerance);
  EXPECT_NEAR(f->coefficients[2], 0.05, kCoefficientTolerance);
  EXPECT_TRUE(pipeline::uses_angle(RestitutionModel::log_mach_inverse_angle));
  EXPECT_EQ(pipeline::model_from_key("log_mach_inverse_angle"),
            RestitutionModel::log_mach_inverse_angle);
  EXPECT_EQ(pipeline::model_formula(RestitutionModel::log_mach_inverse_angle),
            "e = c0 + c1*ln(M) + c2/theta_deg");
  const auto noise = [](int i) { return (i % 2 == 0 ? 1.0 : -1.0) * 0.0003; };
  const auto c = pipeline::choose_restitution_model(synthetic(law, noise));
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->fit().model, RestitutionModel::log_mach_inverse_angle);
}

TEST(RestitutionFit, LeaveOneOutPredictionIgnoresThePoint) {
  auto pts =
      synthetic([](double m, double) { return 0.956 + 0.25 / (m * m); }, [](int) { return 0.0; });
  pts[4].restitution = 0.5;  // an outlier: its own fit would be pulled, the left-out one is not
  const auto e = pipeline::leave_one_out_restitution(pts, RestitutionModel::inverse_mach2, 4);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(*e, 0.956 + 0.25 / (pts[4].mach * pts[4].mach), kCoefficientTolerance);
}

TEST(CalibrationTraining, DefaultSetAvoidsTheCaseStudies) {
  const pipeline::CalibrateOptions o;
  std::vector<std::string> wedges;
  for (const auto& p : pipeline::case_study_scenes()) wedges.push_back(p);
  const auto cases = pipeline::wedge_points(wedges);
  ASSERT_GE(cases.size(), 3u);  // M3/10, M4/15, M5/20
  const auto train = pipeline::training_wedges(o.machs, o.angles_deg, 1.4, cases);
  // Seven Mach numbers x nine deflections, all attached; the grid passes
  // through M5/20, which stays out.
  EXPECT_EQ(train.size(), 62u);
  for (const auto& t : train)
    for (const auto& c : cases)
      EXPECT_FALSE(pipeline::same_wedge(t, c)) << t.mach << " / " << t.angle_deg;
  // Even a grid through a case study leaves it out.
  const auto through = pipeline::training_wedges({3.0, 4.0}, {10.0, 15.0}, 1.4, cases);
  ASSERT_EQ(through.size(), 2u);  // M3/15, M4/10
  for (const auto& t : through)
    for (const auto& c : cases) EXPECT_FALSE(pipeline::same_wedge(t, c));
}

TEST(CalibrationTraining, DetachedWedgesAreLeftOut) {
  // Mach 1.5 detaches above ~12 deg at gamma 1.4.
  const auto t = pipeline::training_wedges({1.5}, {8.0, 20.0}, 1.4, {});
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].angle_deg, 8.0);
  const auto s = pipeline::training_scene(t[0]);
  ASSERT_TRUE(s.body.has_value());
  EXPECT_DOUBLE_EQ(s.freestream.mach, 1.5);
  EXPECT_FALSE(s.granular.restitution_given);  // granular settings at their defaults
  // but the averaging, that of the shipped table's sweeps (not the attached
  // shocks' default 16)
  EXPECT_TRUE(s.granular.averaging_given);
  EXPECT_DOUBLE_EQ(s.granular.averaging, 4.0);
  // `pipeline calibrate --averaging` sweeps at another averaging (the Mach
  // 9-10 crossings at predict's 12).
  const auto s12 = pipeline::training_scene(t[0], 12.0);
  EXPECT_DOUBLE_EQ(s12.granular.averaging, 12.0);
  EXPECT_EQ(s12.name, s.name);
}

TEST(RestitutionFit, ACurvatureInMachIsRecoveredAndChosenOnASevenMachGrid) {
  // Crossings bent in ln M (as the 34-wedge grid's are) on seven Mach numbers
  // 2.5-6 and five deflections 8-20 deg, noise 0.0002: (ln M)^2 + 1/theta
  // recovers the law and wins out of sample over the straight ln M.
  const auto law = [](double m, double a) {
    const double l = std::log(m);
    return 0.99 + 0.003 * l - 0.012 * l * l + 0.095 / a;
  };
  std::vector<RestitutionPoint> pts;
  int i = 0;
  for (const double m : {2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0})
    for (const double a : {8.0, 11.0, 14.0, 17.0, 20.0})
      pts.push_back({m, a, law(m, a) + (i++ % 2 == 0 ? 1.0 : -1.0) * 0.0002, 0.001});
  const auto c = pipeline::choose_restitution_model(pts);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->fit().model, RestitutionModel::log_mach2_inverse_angle);
  constexpr double kNoisyCoefficientTolerance = 2e-3;
  EXPECT_NEAR(c->fit().coefficients[2], -0.012, kNoisyCoefficientTolerance);
  EXPECT_NEAR(c->fit().evaluate(3.0, 10.0), law(3.0, 10.0), 3e-4);
  EXPECT_EQ(pipeline::model_from_key("log_mach2_inverse_angle"),
            RestitutionModel::log_mach2_inverse_angle);
  EXPECT_EQ(pipeline::parameter_count(RestitutionModel::log_mach2_inverse_angle), 4u);
  EXPECT_TRUE(pipeline::uses_angle(RestitutionModel::log_mach2_inverse_angle));
}

TEST(RestitutionFit, AMinimumInTheDeflectionIsRecoveredAndChosenOnAWideGrid) {
  // Crossings that fall as 1/theta and turn up again towards detachment (as
  // the 8-26 deg training grid's do), noise 0.0002: theta^2 on top of
  // (ln M)^2 + 1/theta follows the turn, 1/theta alone cannot, and out of
  // sample the richer form wins.
  const auto law = [](double m, double a) {
    const double l = std::log(m);
    return 0.98 + 0.003 * l - 0.012 * l * l + 0.1 / a + 1.2e-5 * a * a;
  };
  std::vector<RestitutionPoint> pts;
  int i = 0;
  for (const double m : {2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0})
    for (const double a : {8.0, 11.0, 14.0, 17.0, 20.0, 23.0, 26.0})
      pts.push_back({m, a, law(m, a) + (i++ % 2 == 0 ? 1.0 : -1.0) * 0.0002, 0.001});
  const auto c = pipeline::choose_restitution_model(pts);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->fit().model, RestitutionModel::log_mach2_inverse_angle_angle2);
  constexpr double kLawTolerance = 3e-4;
  EXPECT_NEAR(c->fit().evaluate(3.0, 24.5), law(3.0, 24.5), kLawTolerance);
  EXPECT_NEAR(c->fit().evaluate(5.2, 9.5), law(5.2, 9.5), kLawTolerance);
  EXPECT_EQ(pipeline::model_from_key("log_mach2_inverse_angle_angle2"),
            RestitutionModel::log_mach2_inverse_angle_angle2);
  EXPECT_EQ(pipeline::parameter_count(RestitutionModel::log_mach2_inverse_angle_angle2), 5u);
  EXPECT_TRUE(pipeline::uses_angle(RestitutionModel::log_mach2_inverse_angle_angle2));
}
