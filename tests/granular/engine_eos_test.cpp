// Equation of state of elastic hard disks: the compressibility factor from
// the collisional virial against Henderson's (1 + nu^2/8) / (1 - nu)^2.
#include <gtest/gtest.h>

#include "engine_support.hpp"

namespace granular {
namespace {

// Issue 3: within 1% of Henderson for packing fractions 0.1 to 0.5.
constexpr double kEosTolerance = 0.01;
constexpr int kParticles = 2000;
constexpr double kMeltPerParticle = 30.0;
constexpr double kMeasurePerParticle = 150.0;

class EngineEos : public ::testing::TestWithParam<double> {};

TEST_P(EngineEos, CompressibilityFactorMatchesHenderson) {
  const double nu = GetParam();
  SCOPED_TRACE("seed 11");
  Engine e = test::melted_box(kParticles, nu, kMeltPerParticle, 11);
  e.reset_measurement();
  e.run_collisions(static_cast<std::uint64_t>(kMeasurePerParticle * kParticles));
  const double z = 1.0 + e.virial_sum() / (2.0 * e.energy_time_integral());
  EXPECT_NEAR(z / granular::henderson_z(nu), 1.0, kEosTolerance) << "nu " << nu << " Z " << z;
}

INSTANTIATE_TEST_SUITE_P(PackingFractions, EngineEos, ::testing::Values(0.1, 0.2, 0.3, 0.4, 0.5));

}  // namespace
}  // namespace granular
