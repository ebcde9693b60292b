// The plateau rule of precision on demand on made-up check sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "granular/precision_stop.hpp"

namespace {

using granular::PrecisionCheck;

// Checks at 1, 1.5, 2, ... flow-through times (the flow run's schedule).
std::vector<PrecisionCheck> checks(double (*width)(double), int n, const char* quantity = "shock_angle") {
  std::vector<PrecisionCheck> c;
  for (int k = 0; k < n; ++k) {
    const double t = 1.0 + 0.5 * k;
    c.push_back({t, width(t), quantity});
  }
  return c;
}

}  // namespace

TEST(PrecisionStop, StatisticalNarrowingNeverPlateaus) {
  // 1/sqrt(t): doubling the time gives 0.71 of the width, below 0.9.
  const auto c = checks([](double t) { return 0.1 / std::sqrt(t); }, 30);
  for (std::size_t n = 1; n <= c.size(); ++n)
    EXPECT_FALSE(granular::interval_plateaued({c.begin(), c.begin() + static_cast<long>(n)})) << n;
}

TEST(PrecisionStop, AFlatIntervalStopsAtTheSecondCheckThatDoubledItsTime) {
  const auto c = checks([](double) { return 0.05; }, 6);
  // At 2 (against 1) alone: one stalled check is not enough; at 2.5 (against 1) the second.
  EXPECT_FALSE(granular::interval_plateaued({c.begin(), c.begin() + 3}));
  EXPECT_TRUE(granular::interval_plateaued({c.begin(), c.begin() + 4}));
}

TEST(PrecisionStop, AFloorUnderStatisticalNoisePlateausOnceTheNoiseIsSmall) {
  // sqrt(floor^2 + noise^2 / t): narrows at first, then stalls at the floor;
  // the rule stops where noise^2 / t <= 0.31 floor^2 (t ~ 13 here), within 15%
  // of the floor.
  const auto c = checks([](double t) { return std::sqrt(0.01 * 0.01 + 0.02 * 0.02 / t); }, 60);
  std::size_t stop = 0;
  for (std::size_t n = 2; n <= c.size() && !stop; ++n)
    if (granular::interval_plateaued({c.begin(), c.begin() + static_cast<long>(n)})) stop = n;
  ASSERT_GT(stop, 0u);
  const double t = c[stop - 1].flow_throughs;
  EXPECT_GT(t, 4.0);   // not while the noise still dominates
  EXPECT_LT(c[stop - 1].half_width, 1.15 * 0.01);
}

TEST(PrecisionStop, NeedsOneQuantityAndFiniteWidths) {
  auto c = checks([](double) { return 0.05; }, 4);
  c[0].quantity = "standoff";  // the check it is compared with is of another kind
  EXPECT_FALSE(granular::interval_plateaued(c));
  c = checks([](double) { return 0.05; }, 4);
  c[3].half_width = std::nan("");
  EXPECT_FALSE(granular::interval_plateaued(c));
}

TEST(PrecisionStop, AGrowingIntervalIsNoPlateau) {
  // The disc M3.5's standoff half-widths while its bow shock settled (0.050,
  // 0.037, 0.066, 0.097 at 1-2.5 flow-through times): grown to twice its
  // width at half the time, so averaging goes on; flat after it, it stops
  // once both last checks compare with flat ones (6 and 6.5 against 3).
  std::vector<PrecisionCheck> c{{1.0, 0.050, "standoff"},
                                {1.5, 0.037, "standoff"},
                                {2.0, 0.066, "standoff"},
                                {2.5, 0.097, "standoff"}};
  EXPECT_FALSE(granular::interval_plateaued(c));
  for (double t = 3.0; t <= 6.5; t += 0.5) c.push_back({t, 0.06, "standoff"});
  EXPECT_TRUE(granular::interval_plateaued(c));
}

TEST(PrecisionStop, ExpectedSavingFollowsTheStatisticalNarrowing) {
  // Later stages whose CPU is linear in the half-width: averaging 1 more
  // flow-through time after 3 takes the width to sqrt(3/4) of itself.
  const auto linear = [](double, double hw) { return 10.0 * hw; };
  EXPECT_NEAR(granular::expected_saving(linear, 20.0, 0.4, 3.0, 1.0),
              10.0 * 0.4 * (1.0 - std::sqrt(0.75)), 1e-12);
  // Later stages that do not see the width save nothing.
  EXPECT_EQ(granular::expected_saving([](double, double) { return 5.0; }, 20.0, 0.4, 3.0, 1.0),
            0.0);
  // Costs that move in steps: the chunk gets its share of the whole step
  // between an exact shock and this width, whether or not its own narrowing
  // crosses it, and a price that falls with the width saves nothing.
  const auto step = [](double, double hw) { return hw > 0.2 ? 12.0 : 10.0; };
  EXPECT_NEAR(granular::expected_saving(step, 20.0, 0.4, 3.0, 1.0), 2.0 * (1.0 - std::sqrt(0.75)),
              1e-12);
  const auto falling = [](double, double hw) { return 10.0 - hw; };
  EXPECT_EQ(granular::expected_saving(falling, 20.0, 0.4, 3.0, 1.0), 0.0);
  // Nothing priced, nothing averaged yet, or no more averaging: no figure.
  EXPECT_TRUE(std::isnan(granular::expected_saving({}, 20.0, 0.4, 3.0, 1.0)));
  EXPECT_TRUE(std::isnan(granular::expected_saving(linear, 20.0, 0.4, 0.0, 1.0)));
  EXPECT_TRUE(std::isnan(granular::expected_saving(linear, 20.0, 0.4, 3.0, 0.0)));
}

TEST(PrecisionStop, AChunkPaysUnlessItSavesLessThanItCosts) {
  EXPECT_TRUE(granular::chunk_pays(2.0, 1.0));
  EXPECT_TRUE(granular::chunk_pays(1.0, 1.0));
  EXPECT_FALSE(granular::chunk_pays(0.5, 1.0));
  EXPECT_FALSE(granular::chunk_pays(0.0, 1e-6));
  // What cannot be priced is not held against the averaging.
  EXPECT_TRUE(granular::chunk_pays(std::nan(""), 1.0));
}
