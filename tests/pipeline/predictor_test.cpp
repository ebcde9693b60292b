// Shock predictors behind the registry: the correlation (fast, exact on
// attached wedges), the coarse CFD run (real gmsh and OpenFOAM, slow), and
// `pipeline predict`'s bad input.
#include "pipeline/predictor.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "meshgen/mesh.hpp"
#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
using scene::kDeg;
using scene::kNaN;
const std::string kPipeline = std::string(BIN_DIR) + "/pipeline";
const std::string kData = std::string(SOURCE_DIR) + "/tests/data";

fs::path fresh(const std::string& name) {
  return test_support::absent_dir("shockgrain_predictor_" + name);
}

int run_cli(const std::string& args) {
  const int rc = std::system((kPipeline + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
}  // namespace

TEST(Predictor, RegistryNamesEveryPredictorAndRefusesUnknownOnes) {
  for (const auto& n : pipeline::predictor_names())
    EXPECT_EQ(pipeline::make_predictor(n)->name(), n);
  try {
    (void)pipeline::make_predictor("hessian");
    FAIL() << "unknown predictor accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("granular, correlation, coarse_cfd, adapt"),
              std::string::npos)
        << e.what();
  }
}

TEST(Predictor, CorrelationIsTheExactObliqueShockOnAnAttachedWedge) {
  const auto s =
      scene::parse_scene("name: w\nbody: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const auto dir = fresh("corr_wedge");
  const auto p = pipeline::predict_shock(s, "correlation", dir.string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::attached);
  const double beta = *scene::oblique_shock_beta(3.0, 10 * kDeg, 1.4);
  EXPECT_NEAR(p.shock_angle_deg, beta / kDeg, 1e-9);
  ASSERT_GE(p.curve.size(), 2u);
  for (const auto& q : p.curve) EXPECT_NEAR(q.y, q.x * std::tan(beta), 1e-9);
  // meshgen reads what the predictor wrote, every point accepted.
  const auto req = meshgen::request_from_shock_csv(p.shock_csv);
  EXPECT_EQ(req.shock_curve.size(), p.curve.size());
  EXPECT_LT(p.cpu_seconds, 1.0);
}

TEST(Predictor, CorrelationIsBilligsShockOnADisc) {
  const auto s =
      scene::parse_scene("name: d\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n");
  const auto p = pipeline::predict_shock(s, "correlation", fresh("corr_disc").string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::detached);
  // Standoff in body lengths (radii): Billig's 0.386 exp(4.67/M^2).
  EXPECT_NEAR(p.standoff, scene::billig_standoff_cylinder(4.0), 1e-12);
  // The vertex stands that far ahead of the nose, on the axis.
  EXPECT_NEAR(p.curve.front().x, -0.5 - 0.5 * scene::billig_standoff_cylinder(4.0), 1e-9);
  EXPECT_NEAR(p.curve.front().y, 0.0, 1e-12);
  // The shape bends downstream, away from the axis.
  EXPECT_GT(p.curve.back().x, p.curve.front().x);
  EXPECT_GT(p.curve.back().y, p.curve.front().y);
}

TEST(Predictor, CorrelationOnApolloStatesItsApproximation) {
  const auto s =
      scene::parse_scene("name: a\nbody: {kind: apollo, diameter: 1}\nfreestream: {mach: 5}\n");
  const auto p = pipeline::predict_shock(s, "correlation", fresh("corr_apollo").string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::detached);
  EXPECT_NE(p.details.value("correlation", "").find("approximation"), std::string::npos)
      << p.details.dump();
  EXPECT_GT(p.standoff_ci, 0.2 * p.standoff) << "an approximate correlation must carry a wide band";
}

TEST(Predictor, PredictCommandRefusesBadInput) {
  const auto out = fresh("cli_bad");
  EXPECT_EQ(run_cli("predict " + kData + "/wedge_verdict.yaml --predictor nonsense --out " +
                    out.string()),
            2);
  EXPECT_EQ(run_cli("predict /nonexistent.yaml --predictor correlation --out " + out.string()), 2);
  EXPECT_EQ(run_cli("predict " + kData + "/wedge_verdict.yaml --out " + out.string()), 2)
      << "--predictor is required";
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

TEST(Predictor, PredictCommandWritesTheContractKeys) {
  const auto out = fresh("cli_ok");
  ASSERT_EQ(run_cli("predict " + kData + "/wedge_verdict.yaml --predictor correlation --out " +
                    out.string()),
            0);
  const auto j = nlohmann::json::parse(scene::read_file((out / "summary.json").string()));
  for (const char* k :
       {"predictor", "shock", "shock_angle_deg", "shock_angle_ci_deg", "cpu_seconds", "reference"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_NEAR(j["reference"]["error"].get<double>(), 0.0, 1e-9);
  EXPECT_TRUE(fs::exists(out / "shock.csv"));
}

TEST(Predictor, ApexRayStartsAtTheApexAndWidensWithTheAngleInterval) {
  const scene::Domain d{-0.2, 1.0, 0.0, 0.8, true};
  constexpr double kAngle = 30.0, kCi = 0.5;
  const auto ray = pipeline::apex_ray(d, {0.0, 0.0}, kAngle, kCi);
  ASSERT_GE(ray.points.size(), 2u);
  ASSERT_EQ(ray.half_width.size(), ray.points.size());
  EXPECT_EQ(ray.points.front().x, 0.0);
  EXPECT_EQ(ray.half_width.front(), 0.0);
  for (std::size_t i = 0; i < ray.points.size(); ++i) {
    const auto q = ray.points[i];
    EXPECT_NEAR(q.y, q.x * std::tan(kAngle * kDeg), 1e-12);
    EXPECT_NEAR(ray.half_width[i], scene::norm(q) * std::tan(kCi * kDeg), 1e-12);
  }
  // It ends where it leaves the domain: the outlet at x = 1 (y = 0.577 < 0.8).
  EXPECT_NEAR(ray.points.back().x, 1.0, 1e-12);
}

// The granular predictor's attached shock as meshgen gets it: the ray from
// the apex at the fitted angle (the stations stand off upstream), the
// stations themselves kept in shockfit/shock.csv.
TEST(Predictor, GranularHandsAnAttachedShockAsTheApexRay) {
  const auto s = scene::load_scene(kData + "/wedge_verdict.yaml");
  const auto dir = fresh("granular_ray");
  const auto p = pipeline::predict_shock(s, "granular", dir.string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::attached);
  ASSERT_GE(p.curve.size(), 2u);
  EXPECT_LT(scene::norm(p.curve.front()), 1e-12) << "the ray starts at the apex";
  for (std::size_t i = 1; i < p.curve.size(); ++i)
    EXPECT_NEAR(std::atan2(p.curve[i].y, p.curve[i].x) / kDeg, p.shock_angle_deg, 1e-9) << i;
  const auto req = meshgen::request_from_shock_csv(p.shock_csv);
  EXPECT_EQ(req.shock_curve.size(), p.curve.size());
  EXPECT_TRUE(fs::exists(dir / "shockfit" / "shock.csv")) << "the measured stations stay";
  // Without a calibration's scatter the band is the fitted angle's own interval.
  const auto end = p.curve.back();
  EXPECT_NEAR(p.half_width.back(), scene::norm(end) * std::tan(p.shock_angle_ci_deg * kDeg), 1e-9);

  // With it (the same cached granular run), the band widens by the
  // calibration's 95% scatter, and the prediction's fingerprint changes so
  // that no grid meshed round the narrower band is reused.
  constexpr double kScatter = 1.2;
  const auto wide = pipeline::predict_shock(s, "granular", dir.string(), 1, false, kScatter);
  EXPECT_EQ(wide.shock_angle_deg, p.shock_angle_deg);
  const double band = std::hypot(p.shock_angle_ci_deg, 1.96 * kScatter);
  EXPECT_NEAR(wide.half_width.back(), scene::norm(end) * std::tan(band * kDeg), 1e-9);
  EXPECT_NEAR(wide.details.at("band_angle_half_width_deg").get<double>(), band, 1e-12);
  EXPECT_NE(wide.fingerprint, p.fingerprint);
}

// A disc at Mach 1.7 with e = 1 (where the wedge table, held at the elastic
// limit, puts it): the granular bow shock stands 4.3 R off, past where the
// domain expects it, and shockfit accepts none of its 40 stations, though it
// reads a standoff on the axis. The predictor places no band and says why,
// so the pipeline runs the uniform family alone instead of failing on an
// empty shock.csv (it had exited 2, "no accepted rows").
TEST(Predictor, GranularBowShockWithoutAcceptedStationsPlacesNoBandAndSaysWhy) {
  const auto s = scene::parse_scene(
      "name: d17\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.7}\ngranular: "
      "{restitution: 1, replicas: 2}\n");
  const auto dir = fresh("granular_no_band");
  const auto p = pipeline::predict_shock(s, "granular", dir.string(), 1);
  EXPECT_EQ(p.kind, scene::ShockKind::detached);
  EXPECT_TRUE(p.curve.empty());
  EXPECT_TRUE(std::isfinite(p.standoff));
  ASSERT_TRUE(p.details.contains("no_band"));
  EXPECT_NE(p.details["no_band"].get<std::string>().find("accepted 0 of 40"), std::string::npos)
      << p.details["no_band"];
}

TEST(Predictor, BandAngleCombinesTheIntervalWithTheCalibrationScatter) {
  EXPECT_NEAR(pipeline::band_angle_half_width_deg(0.6, 1.0), std::hypot(0.6, 1.96), 1e-15);
  EXPECT_EQ(pipeline::band_angle_half_width_deg(0.6, kNaN), 0.6);  // a scene's own restitution
  EXPECT_NEAR(pipeline::band_angle_half_width_deg(kNaN, 1.0), 1.96, 1e-15);
}
