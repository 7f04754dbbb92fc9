// Symplectic Euler, the default translation step and the gyroscopic term, through the World's public API
// (no shapes, so no contacts): free flight follows the exact discrete
// recurrence, torque-free spin conserves angular momentum, and with the
// gyroscopic term (either splitting order) the intermediate axis is
// unstable (Dzhanibekov).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "talus/world.h"

namespace talus {
namespace integrator_test {

constexpr double kH = 1.0 / 60.0;

World MakeWorld(const WorldSettings& settings) {
  auto world = World::Create(settings);
  EXPECT_TRUE(world) << world.GetError().message;
  return std::move(world).Value();
}

Vec3 AngularMomentum(const BodyState& s) {
  const Mat3 r = s.orientation.toRotationMatrix();
  return r * s.localInertia * r.transpose() * s.angularVelocity;
}

TEST(Integrator, FreeFallFollowsTheSymplecticEulerRecurrence) {
  // The write-up's scheme, selected explicitly (the default is exact for
  // constant gravity; tested below).
  World world = MakeWorld({.gravity = {0.0, -9.81, 0.0},
                           .sleeping = false,
                           .methods = {.translation = TranslationIntegrator::SymplecticEuler}});
  const double y0 = 100.0;
  const BodyId id = world.CreateBody({.type = BodyType::Dynamic, .position = {0, y0, 0}}).Value();
  for (int n = 1; n <= 240; ++n) {
    ASSERT_TRUE(world.Step(kH));
    const double t = n * kH;
    // y_n = y0 + v0 t - g t^2 / 2 - g h t / 2, exact for the discrete scheme;
    // the tolerance is round-off of a 100 m coordinate over n additions.
    const double expected = y0 - 0.5 * 9.81 * t * t - 0.5 * 9.81 * kH * t;
    const BodyState s = world.GetBodyState(id).Value();
    EXPECT_NEAR(s.position.y(), expected, 1e-11 * n) << "step " << n;
    EXPECT_NEAR(s.linearVelocity.y(), -9.81 * t, 1e-12 * n);
  }
}

TEST(Integrator, ProjectileFollowsTheRecurrenceOnEveryAxis) {
  const Vec3 g(0.0, -9.81, 0.0);
  World world = MakeWorld(
      {.gravity = g, .sleeping = false, .methods = {.translation = TranslationIntegrator::SymplecticEuler}});
  const Vec3 x0(1.0, 2.0, 3.0);
  const Vec3 v0(4.0, 12.0, -3.0);
  const BodyId id =
      world.CreateBody({.type = BodyType::Dynamic, .position = x0, .linearVelocity = v0, .mass = 7.0})
          .Value();
  for (int n = 1; n <= 180; ++n) {
    ASSERT_TRUE(world.Step(kH));
    const double t = n * kH;
    const Vec3 expected = x0 + v0 * t + 0.5 * g * t * t + 0.5 * g * kH * t;
    EXPECT_LT((world.GetBodyState(id).Value().position - expected).norm(), 1e-11 * n);
  }
}

// The default translation step is exact for constant gravity: with every
// setting at its default (sleeping included: the body never stops), free
// flight lands on x0 + v0 t + g t^2 / 2, not on the symplectic sequence
// g h t / 2 below it.
TEST(Integrator, DefaultFreeFlightFollowsTheParabola) {
  World world = MakeWorld(WorldSettings{});
  const Vec3 g = WorldSettings{}.gravity;
  const Vec3 x0(-3.0, 50.0, 2.0);
  const Vec3 v0(1.5, 9.0, -2.5);
  const BodyId id =
      world.CreateBody({.type = BodyType::Dynamic, .position = x0, .linearVelocity = v0, .mass = 3.0})
          .Value();
  for (int n = 1; n <= 240; ++n) {
    ASSERT_TRUE(world.Step(kH));
    const double t = n * kH;
    const BodyState s = world.GetBodyState(id).Value();
    // Round-off of coordinates below 100 m (ulp 1.4e-14) over n steps; the
    // symplectic lag g h t / 2 is 1.4e-3 n m, 1e9 times more.
    ASSERT_LT((s.position - (x0 + v0 * t + 0.5 * g * t * t)).norm(), 1e-12 * n) << "step " << n;
    ASSERT_LT((s.linearVelocity - (v0 + g * t)).norm(), 1e-12 * n) << "step " << n;
  }
}

// The same closed form, step after step, at several step sizes: the default
// carries no O(h) error, so halving h changes nothing beyond round-off.
TEST(Integrator, DefaultFreeFallIsIndependentOfTheStep) {
  const double y0 = 20.0;
  const double v0 = 4.0;
  const double g = 9.81;
  const double duration = 1.5;
  for (const int steps : {15, 90, 600, 4800}) {
    World world = MakeWorld(WorldSettings{});
    const BodyId id =
        world.CreateBody({.type = BodyType::Dynamic, .position = {0, y0, 0}, .linearVelocity = {0, v0, 0}})
            .Value();
    const double h = duration / steps;
    for (int n = 0; n < steps; ++n) ASSERT_TRUE(world.Step(h));
    const double y = world.GetBodyState(id).Value().position.y();
    // Round-off of a 20 m coordinate over at most 4800 steps.
    EXPECT_NEAR(y, y0 + v0 * duration - 0.5 * g * duration * duration, 1e-12 * steps) << steps << " steps";
  }
}

TEST(Integrator, SpinAboutAPrincipalAxisConservesAngularMomentumWithoutGyroscopicTerm) {
  World world = MakeWorld({.gravity = Vec3::Zero(),
                           .sleeping = false,
                           .methods = {.rotation = RotationIntegrator::ConstantRate}});
  const Mat3 inertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
  const Quat tilt(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  const Vec3 w = tilt * Vec3(0.0, 0.0, 4.0);
  const BodyId id =
      world
          .CreateBody(
              {.type = BodyType::Dynamic, .orientation = tilt, .angularVelocity = w, .localInertia = inertia})
          .Value();
  const Vec3 l0 = AngularMomentum(world.GetBodyState(id).Value());
  for (int n = 0; n < 600; ++n) ASSERT_TRUE(world.Step(kH));
  const BodyState s = world.GetBodyState(id).Value();
  // Round-off only: the rotation is about the fixed axis of w.
  EXPECT_LT((AngularMomentum(s) - l0).norm(), 1e-12 * l0.norm());
  EXPECT_NEAR(s.orientation.norm(), 1.0, 1e-15);
}

// Spin about the intermediate principal axis with a small perturbation: the
// body's intermediate axis periodically turns over (the Dzhanibekov effect),
// which only the gyroscopic term produces.
double MinimumIntermediateAxisAlignment(RotationIntegrator rotation) {
  World world = MakeWorld({.gravity = Vec3::Zero(), .sleeping = false, .methods = {.rotation = rotation}});
  const Mat3 inertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
  const BodyId id =
      world
          .CreateBody(
              {.type = BodyType::Dynamic, .angularVelocity = {0.01, 4.0, 0.0}, .localInertia = inertia})
          .Value();
  double minimum = 1.0;
  for (int n = 0; n < 1200; ++n) {
    EXPECT_TRUE(world.Step(1.0 / 240.0));
    const Vec3 axis = world.GetBodyState(id).Value().orientation * Vec3::UnitY();
    minimum = std::min(minimum, axis.y());
  }
  return minimum;
}

TEST(Integrator, IntermediateAxisFlipsWithGyroscopicTerm) {
  EXPECT_LT(MinimumIntermediateAxisAlignment(RotationIntegrator::MomentumSplitting), -0.9);
  EXPECT_LT(MinimumIntermediateAxisAlignment(RotationIntegrator::MomentumSplittingFourthOrder), -0.9);
}

TEST(Integrator, IntermediateAxisNeverFlipsWithoutGyroscopicTerm) {
  // Without w x Iw the angular velocity is constant in world space: the body
  // just turns about it, the write-up's model.
  EXPECT_GT(MinimumIntermediateAxisAlignment(RotationIntegrator::ConstantRate), 0.99);
}

}  // namespace integrator_test
}  // namespace talus
