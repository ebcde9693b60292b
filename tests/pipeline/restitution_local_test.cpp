// The smooth model's local correction: kept where the data show a lack of
// fit, refused where they do not, fading beyond the training wedges, and
// read back from a table exactly as written.
#include "pipeline/restitution_local.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/calibration.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace {
using pipeline::RestitutionModel;
using pipeline::RestitutionPoint;

// A smooth law of the chosen form (ln M, (ln M)^2, 1/theta, theta^2).
double smooth(double m, double a) {
  const double l = std::log(m);
  return 0.98 + 0.003 * l - 0.012 * l * l + 0.1 / a + 1.2e-5 * a * a;
}
// A turn no separable form follows: 0.002 in e (about 0.5 deg of shock
// angle) around Mach 3.25 and 22 deg, a few training wedges wide.
double bump(double m, double a) {
  const double u = (std::log(m) - std::log(3.25)) / 0.2, v = (a - 22.0) / 3.0;
  return 0.002 * std::exp(-0.5 * (u * u + v * v));
}

template <class Law>
std::vector<RestitutionPoint> grid(Law law, double noise) {
  std::vector<RestitutionPoint> pts;
  int i = 0;
  for (const double m : {2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0})
    for (const double a : {8.0, 11.0, 14.0, 17.0, 20.0, 21.5, 23.0, 24.5, 26.0})
      pts.push_back({m, a, law(m, a) + (i++ % 2 == 0 ? 1.0 : -1.0) * noise, 0.001});
  return pts;
}

pipeline::CalibrationTable table_of(const std::vector<RestitutionPoint>& pts,
                                    const pipeline::ModelChoice& c) {
  pipeline::CalibrationTable t;
  for (const auto& p : pts) {
    pipeline::CalibrationEntry e;
    e.mach = p.mach;
    e.angle_deg = p.angle_deg;
    e.restitution = p.restitution;
    e.restitution_ci = p.restitution_ci;
    t.entries.push_back(e);
  }
  t.model = c.fit().model;
  t.fits = c.candidates;
  return t;
}
// The bump's points, their chosen model and kept correction, and a table
// holding both: what a calibration with a local correction writes.
struct Corrected {
  std::vector<RestitutionPoint> pts;
  pipeline::ModelChoice choice;
  pipeline::LocalCorrection lc;
  pipeline::CalibrationTable table;
};
std::optional<Corrected> corrected_table() {
  const auto pts = grid([](double m, double a) { return smooth(m, a) + bump(m, a); }, 1e-4);
  const auto c = pipeline::choose_restitution_model(pts);
  if (!c) return std::nullopt;
  const auto lc = pipeline::choose_local_correction(pts, c->fit());
  if (!lc) return std::nullopt;
  auto t = table_of(pts, *c);
  pipeline::attach_local_correction(t, lc->bandwidth_log_mach, lc->bandwidth_angle_deg,
                                    lc->loo_rms);
  return Corrected{pts, *c, *lc, t};
}
}  // namespace

TEST(LocalCorrection, TakesOutALackOfFitTheSmoothModelCannotFollow) {
  const auto pts = grid([](double m, double a) { return smooth(m, a) + bump(m, a); }, 1e-4);
  const auto c = pipeline::choose_restitution_model(pts);
  ASSERT_TRUE(c.has_value());
  ASSERT_EQ(c->fit().model, RestitutionModel::log_mach2_inverse_angle_angle2);
  const auto lc = pipeline::choose_local_correction(pts, c->fit());
  ASSERT_TRUE(lc.has_value());
  EXPECT_LT(lc->loo_rms, 0.9 * c->fit().loo_rms);
  // Between training wedges, inside the turn: the corrected model is at
  // least twice as close to the law as the smooth one.
  const double m = 3.25, a = 22.0, truth = smooth(m, a) + bump(m, a);
  const double plain = std::abs(c->fit().evaluate(m, a) - truth);
  const double corrected = std::abs(c->fit().evaluate(m, a) + lc->evaluate(m, a) - truth);
  EXPECT_GT(plain, 5e-4);
  EXPECT_LT(corrected, 0.5 * plain);
  // Far from every training wedge the correction fades to the smooth model.
  constexpr double kFaded = 1e-9;
  EXPECT_NEAR(lc->evaluate(20.0, 60.0), 0.0, kFaded);
}

TEST(LocalCorrection, IsRefusedWhereTheSmoothModelFits) {
  // The law itself with alternating noise: the residuals are noise, and a
  // kernel average of them does not lower the leave-one-out error.
  const auto pts = grid(smooth, 2e-4);
  const auto c = pipeline::choose_restitution_model(pts);
  ASSERT_TRUE(c.has_value());
  EXPECT_FALSE(pipeline::choose_local_correction(pts, c->fit()).has_value());
  // A Mach-only model has no deflection to correct in.
  auto mach_only = *pipeline::fit_restitution(pts, RestitutionModel::inverse_mach2);
  mach_only.loo_rms = 1.0;
  EXPECT_FALSE(pipeline::choose_local_correction(pts, mach_only).has_value());
}

TEST(LocalCorrection, ATableReadBackEvaluatesAsWritten) {
  const auto x = corrected_table();
  ASSERT_TRUE(x.has_value());
  const auto& pts = x->pts;
  const auto* c = &x->choice;
  const auto* lc = &x->lc;
  const auto& t = x->table;
  const std::string dir = test_support::fresh_dir("restitution_local");
  const std::string path = dir + "/table.yaml";
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.local_correction.has_value());
  EXPECT_EQ(back.local_correction->bandwidth_log_mach, lc->bandwidth_log_mach);
  EXPECT_EQ(back.local_correction->bandwidth_angle_deg, lc->bandwidth_angle_deg);
  for (const auto& [m, a] : {std::pair{3.25, 22.0}, {4.7, 12.5}, {5.5, 25.0}})
    EXPECT_EQ(*pipeline::interpolate_restitution(back, m, a),
              *pipeline::interpolate_restitution(t, m, a));
  // Attached wedges take the correction; blunt bodies (no angle) do not.
  const double m = 3.25, a = 22.0;
  EXPECT_NE(*pipeline::interpolate_restitution(back, m, a), c->fit().evaluate(m, a));
  EXPECT_EQ(*pipeline::interpolate_restitution(back, m, NAN),
            *pipeline::interpolate_restitution(table_of(pts, *c), m, NAN));

  // A wedge scene takes the corrected e, and its note says so.
  auto wedge = scene::parse_scene("body: {kind: wedge, angle_deg: 22}\nfreestream: {mach: 3.25}\n");
  const auto applied = pipeline::apply_calibration(wedge, path);
  EXPECT_NE(applied.note.find("local correction"), std::string::npos) << applied.note;
  EXPECT_NEAR(wedge.granular.restitution, *pipeline::interpolate_restitution(back, m, a),
              pipeline::kRestitutionQuantum);

  // A malformed correction names its key.
  std::string text;
  {
    std::ifstream in(path);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find("h_angle_deg: ");
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find_first_of(",}", at);
  const std::string broken = text.substr(0, at) + "h_angle_deg: 0" + text.substr(end);
  const std::string bad_path = dir + "/broken.yaml";
  std::ofstream(bad_path) << broken;
  try {
    pipeline::read_calibration(bad_path);
    FAIL() << "a zero bandwidth was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("local_correction.h_angle_deg"), std::string::npos)
        << e.what();
  }
}

// A table extended by crossings far outside its range keeps its own widths
// when asked: the held pair is the only one tried, and its left-out error is
// never below the best of the grid's.
TEST(LocalCorrection, HeldWidthsAreTheOnesUsed) {
  const auto pts = grid([](double m, double a) { return smooth(m, a) + bump(m, a); }, 1e-4);
  const auto c = pipeline::choose_restitution_model(pts);
  ASSERT_TRUE(c.has_value());
  const auto free = pipeline::choose_local_correction(pts, c->fit());
  ASSERT_TRUE(free.has_value());
  const pipeline::CorrectionWidths held{free->bandwidth_log_mach == 0.2 ? 0.1 : 0.2,
                                        free->bandwidth_angle_deg};
  const auto kept = pipeline::choose_local_correction(pts, c->fit(), held);
  ASSERT_TRUE(kept.has_value());
  EXPECT_DOUBLE_EQ(kept->bandwidth_log_mach, held.log_mach);
  EXPECT_DOUBLE_EQ(kept->bandwidth_angle_deg, held.angle_deg);
  EXPECT_GE(kept->loo_rms, free->loo_rms);
}

// A table extended by crossings far beyond its Mach range (`--from-points
// TABLE NEW.json --extend`) keeps its correction's widths and its measured
// angle scatter, and e inside its range stays where its correction had it.
TEST(LocalCorrection, AnExtendedTableKeepsItsWidthsAndScatter) {
  const auto law = [](double m, double a) { return smooth(m, a) + bump(m, a); };
  const auto corrected = corrected_table();
  ASSERT_TRUE(corrected.has_value());
  const auto* lc = &corrected->lc;
  auto t = corrected->table;
  t.angle_scatter = pipeline::AngleScatter{0.18, 0.23, 12.0, 120, 40, 2.6, 5.9};
  const std::string dir = test_support::fresh_dir("restitution_extend");
  pipeline::write_calibration(t, dir + "/first.yaml");
  nlohmann::json far;
  far["crossings"] = nlohmann::json::array();
  for (const double a : {8.0, 14.0, 20.0, 26.0})
    far["crossings"].push_back({{"mach", 10.0},
                                {"angle_deg", a},
                                {"restitution", law(10.0, a) - 0.004},
                                {"restitution_ci", 0.002}});
  scene::write_file_atomic(dir + "/far.json", far.dump());
  const auto r = pipeline::calibrate_from_points({dir + "/first.yaml", dir + "/far.json"},
                                                 dir + "/extended.yaml", true);
  EXPECT_TRUE(r["angle_scatter_kept"].get<bool>());
  const auto x = pipeline::read_calibration(dir + "/extended.yaml");
  ASSERT_TRUE(x.local_correction.has_value());
  EXPECT_EQ(x.local_correction->bandwidth_log_mach, lc->bandwidth_log_mach);
  EXPECT_EQ(x.local_correction->bandwidth_angle_deg, lc->bandwidth_angle_deg);
  ASSERT_TRUE(x.angle_scatter.has_value());
  EXPECT_DOUBLE_EQ(x.angle_scatter->deg, 0.18);
  EXPECT_DOUBLE_EQ(pipeline::training_mach_range(x)->high, 10.0);
  // Inside the old range, well away from Mach 10: e within the tolerance
  // the extension is judged by (0.0005, about 0.1 deg at the steepest).
  constexpr double kInsideMove = 5e-4;
  for (const auto& [m, a] : {std::pair{3.25, 22.0}, {2.8, 12.5}, {4.2, 17.0}})
    EXPECT_NEAR(*pipeline::interpolate_restitution(x, m, a),
                *pipeline::interpolate_restitution(t, m, a), kInsideMove)
        << m << " / " << a;
}
