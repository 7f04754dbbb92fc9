// Closed-form truths against direct simulation of the integrator they
// describe, and the combine rules against their definitions.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/scenario/scenario.h"

namespace talus::harness {
namespace truths_test {

TEST(Truths, SymplecticEulerFreeFallMatchesSteppingTheIntegrator) {
  const double h = 1.0 / 60.0, g = 9.81;
  double y = 10.0, v = 2.0;
  for (int n = 1; n <= 600; ++n) {
    v -= g * h;
    y += h * v;
    // Round-off of 600 additions of values ~10: 1e-11 is far above it and far below the g h t / 2 gap.
    ASSERT_NEAR(FreeFallHeightSymplecticEuler(10.0, 2.0, g, h, n), y, 1e-11) << "step " << n;
  }
  const double t = 600 * h;
  EXPECT_NEAR(FreeFallHeight(10.0, 2.0, g, t) - y, 0.5 * g * h * t, 1e-11);
}

TEST(Truths, SymplecticEulerStopDistanceMatchesSteppingAndConvergesToTheFormula) {
  const double v0 = 3.0, mu = 0.5, g = 9.81, h = 1.0 / 240.0;
  double x = 0.0, v = v0;
  while (true) {
    v = std::max(0.0, v - mu * g * h);
    if (v == 0.0) break;
    x += h * v;
  }
  EXPECT_NEAR(SlidingStopDistanceSymplecticEuler(v0, mu, g, h), x, 1e-12);
  // The discrete sum misses about v0 h / 2 of the integral.
  EXPECT_NEAR(SlidingStopDistance(v0, mu, g), x, v0 * h);
  EXPECT_NEAR(SlidingStopDistance(3.0, 0.5, 9.81), 9.0 / 9.81, 1e-15);
}

TEST(Truths, BounceApexesShrinkByESquared) {
  const auto heights = BounceApexHeights(2.0, 0.5, 3);
  ASSERT_EQ(heights.size(), 3u);
  EXPECT_DOUBLE_EQ(heights[0], 0.5);
  EXPECT_DOUBLE_EQ(heights[1], 0.125);
  EXPECT_DOUBLE_EQ(heights[2], 0.03125);
}

TEST(Truths, CombineRulesFollowTheirDefinitions) {
  EXPECT_DOUBLE_EQ(Combine(CombineRule::Sqrt, 0.25, 0.64), 0.4);
  EXPECT_EQ(Combine(CombineRule::Min, 0.2, 0.7), 0.2);
  EXPECT_EQ(Combine(CombineRule::Max, 0.2, 0.7), 0.7);
  EXPECT_DOUBLE_EQ(Combine(CombineRule::Multiply, 0.2, 0.7), 0.14);
  EXPECT_DOUBLE_EQ(Combine(CombineRule::Average, 0.2, 0.7), 0.45);
  EXPECT_STREQ(CombineRuleName(CombineRule::Sqrt), "sqrt");
}

}  // namespace truths_test
}  // namespace talus::harness
