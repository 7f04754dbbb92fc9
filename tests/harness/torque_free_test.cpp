// Torque-free spin: the RK4 flip interval against the closed form in
// complete elliptic integrals (Landau and Lifshitz, Mechanics, section 37),
// the invariants along the integration, and the refused inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "talus/harness/analytic/torque_free_motion.h"

namespace talus::harness {
namespace torque_free_test {

// Half the period of the body-frame angular velocity, from the invariants:
// with I1 < I2 < I3, L^2 > 2 E I2 (else swap I1 and I3),
// T = 4 K(k) sqrt(I1 I2 I3 / ((I3 - I2)(L^2 - 2 E I1))),
// k^2 = (I2 - I1)(2 E I3 - L^2) / ((I3 - I2)(L^2 - 2 E I1)).
// The intermediate component changes sign twice per period.
double EllipticFlipInterval(const Vec3& inertia, const Vec3& omega) {
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return inertia[a] < inertia[b]; });
  double i1 = inertia[order[0]], i2 = inertia[order[1]], i3 = inertia[order[2]];
  const Vec3 momentum = inertia.cwiseProduct(omega);
  const double l2 = momentum.squaredNorm();
  const double e2 = omega.dot(momentum);
  if (l2 < e2 * i2) std::swap(i1, i3);
  const double k2 = (i2 - i1) * (e2 * i3 - l2) / ((i3 - i2) * (l2 - e2 * i1));
  const double period =
      4.0 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(i1 * i2 * i3 / ((i3 - i2) * (l2 - e2 * i1)));
  return 0.5 * period;
}

TEST(TorqueFree, FlipIntervalMatchesTheEllipticClosedForm) {
  const Vec3 box(3.255208333333333, 11.067708333333332, 13.020833333333332);  // the shipped box
  const std::array<std::pair<Vec3, Vec3>, 5> cases = {{
      {box, Vec3(0.02, 3.0, 0.005)},
      {box, Vec3(0.1, 3.0, -0.05)},
      {box, Vec3(0.001, 1.0, 0.0005)},
      {Vec3(1.0, 2.0, 3.0), Vec3(0.05, 2.0, 0.05)},
      {Vec3(5.0, 1.0, 2.0), Vec3(0.02, 0.03, -4.0)},  // intermediate axis z, listed last
  }};
  for (const auto& [inertia, omega] : cases) {
    auto interval = IntermediateAxisFlipInterval(inertia, omega);
    ASSERT_TRUE(interval) << interval.GetError().message;
    // RK4 at 4096 steps per turn and linear interpolation of the crossing:
    // far below 1e-6 relative; the closed form is exact.
    EXPECT_NEAR(interval.Value(), EllipticFlipInterval(inertia, omega), 1e-6 * interval.Value())
        << omega.transpose();
  }
}

TEST(TorqueFree, SmallerPerturbationsFlipMoreSlowly) {
  const Vec3 inertia(1.0, 2.0, 3.0);
  double previous = 0.0;
  for (const double epsilon : {0.1, 0.01, 0.001}) {
    const double interval = IntermediateAxisFlipInterval(inertia, Vec3(epsilon, 1.0, epsilon)).Value();
    EXPECT_GT(interval, previous);
    previous = interval;
  }
}

TEST(TorqueFree, Rk4KeepsBothInvariants) {
  const Vec3 inertia(1.0, 2.0, 3.0);
  Vec3 omega(0.3, 2.0, -0.4);
  const SpinInvariants start = ComputeSpinInvariants(inertia, omega);
  for (int i = 0; i < 20000; ++i) omega = EulerEquationsRk4Step(inertia, omega, 1e-3);
  const SpinInvariants end = ComputeSpinInvariants(inertia, omega);
  // RK4's global error at dt = 1e-3 over 20 s: ~1e-11 relative.
  EXPECT_NEAR(end.energy, start.energy, 1e-9 * start.energy);
  EXPECT_NEAR(end.angularMomentum, start.angularMomentum, 1e-9 * start.angularMomentum);
  EXPECT_DOUBLE_EQ(start.energy, 0.5 * (0.09 + 2.0 * 4.0 + 3.0 * 0.16));
}

TEST(TorqueFree, EulerRateVanishesForSpinAboutAPrincipalAxis) {
  EXPECT_EQ(EulerEquationsRate(Vec3(1, 2, 3), Vec3(0, 5, 0)), Vec3::Zero());
  // I1 w1' = (I2 - I3) w2 w3 = (2 - 3) * 1 * 1.
  EXPECT_DOUBLE_EQ(EulerEquationsRate(Vec3(1, 2, 3), Vec3(0, 1, 1)).x(), -1.0);
}

TEST(TorqueFree, IntermediateAxisIsTheMiddleMoment) {
  EXPECT_EQ(IntermediateAxis(Vec3(1, 2, 3)), 1);
  EXPECT_EQ(IntermediateAxis(Vec3(3, 1, 2)), 2);
  EXPECT_EQ(IntermediateAxis(Vec3(2, 3, 1)), 0);
  EXPECT_EQ(IntermediateAxis(Vec3(1, 1, 3)), -1);
}

TEST(TorqueFree, FlipIntervalRefusesInputsWithoutAFlip) {
  auto symmetric = IntermediateAxisFlipInterval(Vec3(1, 2, 2), Vec3(0.01, 1, 0.01));
  ASSERT_FALSE(symmetric);
  EXPECT_NE(symmetric.GetError().message.find("no intermediate axis"), std::string::npos);
  auto offAxis = IntermediateAxisFlipInterval(Vec3(1, 2, 3), Vec3(0, 0.1, 1));
  ASSERT_FALSE(offAxis);
  EXPECT_NE(offAxis.GetError().message.find("not within 25 degrees"), std::string::npos);
  auto exact = IntermediateAxisFlipInterval(Vec3(1, 2, 3), Vec3(0, 1, 0));  // an exact equilibrium
  ASSERT_FALSE(exact);
  EXPECT_NE(exact.GetError().message.find("does not turn over"), std::string::npos);
}

}  // namespace torque_free_test
}  // namespace talus::harness
