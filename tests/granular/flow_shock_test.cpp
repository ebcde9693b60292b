// The shipped wedge case with the default parameters: a clean oblique shock
// at the granular angle (slow: the full default run).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "flow_support.hpp"
#include "granular/flow_run.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/scene.hpp"

TEST(FlowShock, WedgeM3DefaultSceneShockAngle) {
  const scene::Scene s = scene::load_scene(std::string(SOURCE_DIR) + "/pipeline/cases/wedge_M3_10.yaml");
  granular::RunOptions o;
  o.np = 2;
  const granular::FlowResult r = granular::run_flow_scene(s, o);
  const double nu_inf = r.summary["packing_fraction"].get<double>();
  const auto fit = flowtest::fit_wedge_shock(r.fields, 1.5 * nu_inf, 0.3, 0.9);
  ASSERT_TRUE(fit.has_value());
  const double beta_gas = *scene::oblique_shock_beta(3.0, 10 * std::numbers::pi / 180, 2.0) * 180 / std::numbers::pi;
  std::printf("granular shock angle %.2f +- %.2f deg (%d columns); gamma=2 gas %.2f deg\n", fit->angle_deg,
              fit->angle_se_deg, fit->points, beta_gas);
  EXPECT_GT(fit->angle_deg, beta_gas - 1.0);
  EXPECT_LT(fit->angle_deg, beta_gas + 10.0);
}
