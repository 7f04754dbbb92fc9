// The stacking, sliding and incline closed forms against direct stepping of
// the integrator they describe, and the incline outcome against an
// independent torque balance about the downhill edge.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "talus/harness/analytic/truths.h"

namespace talus::harness {
namespace motion_truths_test {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(MotionTruths, StopTimeMatchesSteppingTheClampedIntegrator) {
  const double g = 9.81;
  for (const double h : {1.0 / 60.0, 1.0 / 240.0}) {
    for (const double mu : {0.3, 0.5, 0.8}) {
      for (const double v0 : {1.0, 3.0}) {
        double v = v0;
        int steps = 0;
        while (v > 0.0) {
          v = std::max(0.0, v - mu * g * h);
          ++steps;
        }
        // The step count is exact; 1e-12 s allows for round-off in n h.
        EXPECT_NEAR(SlidingStopTimeSymplecticEuler(v0, mu, g, h), steps * h, 1e-12) << mu << " " << v0;
        // The discrete stop rounds the continuous time up by less than a step.
        const double t = SlidingStopTime(v0, mu, g);
        EXPECT_GE(steps * h, t - 1e-12);
        EXPECT_LT(steps * h, t + h);
      }
    }
  }
  EXPECT_DOUBLE_EQ(SlidingStopTime(3.0, 0.5, 9.81), 6.0 / 9.81);
}

// The time the speed first falls below a threshold, against stepping the
// clamped integrator, at steps where the threshold is crossed several steps
// before the stop (1 cm/s at 1/960 s is 3 steps for mu 0.3).
TEST(MotionTruths, SlowTimeMatchesSteppingTheClampedIntegrator) {
  const double g = 9.81;
  for (const double h : {1.0 / 60.0, 1.0 / 480.0, 1.0 / 960.0}) {
    for (const double mu : {0.3, 0.5, 0.8}) {
      for (const double v0 : {0.005, 1.0, 3.0}) {
        for (const double speed : {0.01, 0.1}) {
          double v = v0;
          int steps = 0;
          while (!(v < speed)) {
            v = std::max(0.0, v - mu * g * h);
            ++steps;
          }
          // Exact step count; 1e-12 s of round-off in n h.
          EXPECT_NEAR(SlidingSlowTimeSymplecticEuler(v0, mu, g, h, speed), steps * h, 1e-12)
              << h << " " << mu << " " << v0 << " " << speed;
          // The continuous crossing lies within the last step before it.
          const double t = SlidingSlowTime(v0, mu, g, speed);
          EXPECT_GE(steps * h, t - 1e-12);
          EXPECT_LT(steps * h, t + h);
        }
      }
    }
  }
  EXPECT_DOUBLE_EQ(SlidingSlowTime(3.0, 0.5, 9.81, 0.0), SlidingStopTime(3.0, 0.5, 9.81));
  EXPECT_DOUBLE_EQ(SlidingSlowTime(0.005, 0.5, 9.81, 0.01), 0.0);
}

TEST(MotionTruths, StackRestHeightsAreHalfLayersAboveTheFloor) {
  EXPECT_DOUBLE_EQ(StackRestHeight(0.0, 0.5, 0), 0.25);
  EXPECT_DOUBLE_EQ(StackRestHeight(0.0, 0.5, 9), 4.75);
  EXPECT_DOUBLE_EQ(StackRestHeight(-1.0, 2.0, 1), 2.0);
}

TEST(MotionTruths, InclineDistanceMatchesSteppingSymplecticEulerAndConverges) {
  const double g = 9.81, mu = 0.5, h = 1.0 / 60.0;
  const double angle = 35.0 * kDegree;
  // The acceleration along the slope from the forces on the block: gravity's
  // component minus kinetic friction mu N with N = m g cos(angle).
  const double a = g * std::sin(angle) - mu * g * std::cos(angle);
  double v = 0.0, x = 0.0;
  for (int n = 1; n <= 240; ++n) {
    v += a * h;
    x += v * h;
    // Round-off of 240 additions of values ~1: 1e-12 m.
    ASSERT_NEAR(InclineDistanceSymplecticEuler(angle, mu, g, h, n), x, 1e-12) << "step " << n;
  }
  const double t = 240 * h;
  EXPECT_NEAR(InclineDistance(angle, mu, g, t), 0.5 * a * t * t, 1e-12);
  // The integrator leads the parabola by a h t / 2.
  EXPECT_NEAR(x - InclineDistance(angle, mu, g, t), 0.5 * a * h * t, 1e-12);
}

TEST(MotionTruths, InclineBelowTheFrictionAngleHolds) {
  const double mu = 0.5;
  const double threshold = std::atan(mu);
  EXPECT_EQ(InclineAcceleration(threshold - 1e-9, mu, 9.81), 0.0);
  EXPECT_EQ(InclineDistanceSymplecticEuler(threshold - 1e-9, mu, 9.81, 0.01, 100), 0.0);
  EXPECT_GT(InclineAcceleration(threshold + 1e-6, mu, 9.81), 0.0);
  EXPECT_EQ(InclineAcceleration(0.0, 0.0, 9.81), 0.0);
}

// Independent oracle: torque about the downhill bottom edge of the forces
// the block feels in its own (possibly accelerating) frame; it turns over
// when that torque turns it downhill.
InclineOutcome TorqueOracle(double angle, double mu, double width, double height) {
  const double g = 1.0;
  // Slope frame: s downhill along the surface, n along the normal.
  const bool held = g * std::sin(angle) <= mu * g * std::cos(angle);
  const double acceleration = held ? 0.0 : g * std::sin(angle) - mu * g * std::cos(angle);
  const double forceS = g * std::sin(angle) - acceleration;  // gravity plus the frame's inertial force
  const double forceN = -g * std::cos(angle);
  // Centre of mass relative to the downhill edge: half a width uphill, half a height up.
  const double rS = -0.5 * width, rN = 0.5 * height;
  const double torque = rS * forceN - rN * forceS;  // > 0 turns back onto the base
  if (torque < 0.0) return InclineOutcome::Tips;
  return held ? InclineOutcome::Stays : InclineOutcome::Slides;
}

TEST(MotionTruths, InclineOutcomeAgreesWithATorqueBalanceOverRandomBoxes) {
  std::mt19937_64 random(20261122);
  std::uniform_real_distribution<double> angle(0.0, 80.0 * kDegree), mu(0.0, 1.5), size(0.05, 2.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    const double a = angle(random), m = mu(random), w = size(random), h = size(random);
    const InclineOutcome outcome = InclineBoxOutcome(a, m, w, h);
    ASSERT_EQ(outcome, TorqueOracle(a, m, w, h)) << a << " " << m << " " << w << " " << h;
    ++counts[static_cast<int>(outcome)];
  }
  // Every outcome is exercised.
  for (const int count : counts) EXPECT_GT(count, 1000);
}

TEST(MotionTruths, TallBoxOnAGrippySlopeTipsPastItsAspectAngle) {
  // 0.2 x 0.8 box, mu 0.8: tips past atan(0.25) = 14.04 degrees, the shipped scenario's sweep.
  EXPECT_EQ(InclineBoxOutcome(10.0 * kDegree, 0.8, 0.2, 0.8), InclineOutcome::Stays);
  EXPECT_EQ(InclineBoxOutcome(18.0 * kDegree, 0.8, 0.2, 0.8), InclineOutcome::Tips);
  EXPECT_EQ(InclineBoxOutcome(30.0 * kDegree, 0.5, 0.5, 0.5), InclineOutcome::Slides);
  EXPECT_STREQ(InclineOutcomeName(InclineOutcome::Tips), "tips");
}

}  // namespace motion_truths_test
}  // namespace talus::harness
