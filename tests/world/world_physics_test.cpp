// The same physics as tests/dynamics, now through the real pipeline (broad
// phase, SAT, clipped manifolds, solver): resting stacks, friction, bounce,
// sleeping and waking, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "talus/world.h"

namespace talus {
namespace world_physics_test {

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

Shape Box(const Vec3& half) { return Shape::CreateBox(half).Value(); }

BodyId AddGround(World& world, double friction = 0.5, double restitution = 0.0) {
  return world
      .CreateBody({.type = BodyType::Static,
                   .position = {0, -0.5, 0},
                   .shape = Box({50, 0.5, 50}),
                   .friction = friction,
                   .restitution = restitution})
      .Value();
}

World MakeWorld(WorldSettings settings) { return World::Create(settings).Value(); }

// Builds a column of ten 1 m boxes on the ground, steps it for 10 s and
// returns the largest vertical and horizontal deviations of any box from
// its analytic rest position ((i + 1/2) m, on the axis), and the largest
// overhang: at each interface, how far the centre of mass of the boxes
// above lies horizontally from the centre of the box that carries them.
// The boxes topple once an overhang passes the half width (0.5 m).
struct ColumnDeviation {
  double vertical = 0.0;
  double horizontal = 0.0;
  double overhang = 0.0;
};

ColumnDeviation RunColumn(const WorldSettings& settings) {
  World world = MakeWorld(settings);
  AddGround(world);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 10; ++i) {
    boxes.push_back(world
                        .CreateBody({.type = BodyType::Dynamic,
                                     .position = {0, i + 0.5, 0},
                                     .shape = Box(Vec3::Constant(0.5)),
                                     .density = 1000.0})
                        .Value());
  }
  ColumnDeviation worst;
  for (int n = 0; n < 600; ++n) {
    EXPECT_TRUE(world.Step(kH));
    std::vector<Vec3> p;
    for (const BodyId box : boxes) p.push_back(world.GetBodyState(box).Value().position);
    for (int i = 0; i < 10; ++i) {
      const Vec3& q = p[static_cast<std::size_t>(i)];
      worst.vertical = std::max(worst.vertical, std::abs(q.y() - (i + 0.5)));
      worst.horizontal = std::max(worst.horizontal, std::hypot(q.x(), q.z()));
    }
    // Equal masses: the centre of mass above interface k is the mean of
    // boxes k..9, carried by box k - 1.
    for (std::size_t k = 1; k < p.size(); ++k) {
      Vec3 above = Vec3::Zero();
      for (std::size_t j = k; j < p.size(); ++j) above += p[j];
      above /= static_cast<double>(p.size() - k);
      worst.overhang =
          std::max(worst.overhang, std::hypot(above.x() - p[k - 1].x(), above.z() - p[k - 1].z()));
    }
  }
  return worst;
}

TEST(WorldPhysics, ColumnOfTenBoxesRestsWithinAMillimetreForTenSeconds) {
  // The requirement, at default settings (sleeping off so every step solves
  // the column). Measured: 0.31 mm vertical (the first steps, whose
  // contacts are all new, sag the column before the extra sweeps converge)
  // and 1e-14 m horizontal.
  WorldSettings settings;
  settings.sleeping = false;
  const ColumnDeviation column = RunColumn(settings);
  EXPECT_LT(column.vertical, 1e-3);
  EXPECT_LT(column.horizontal, 1e-3);
}

TEST(WorldPhysics, ColumnOfTenBoxesStandsWithTheWriteUpSolver) {
  // The write-up's solver (ten fixed sweeps row by row, Baumgarte bias)
  // holds this column only loosely: it must stand, not rest. Standing is
  // judged by the physics of toppling: no box drops (a box that falls off
  // loses at least its half height, 0.5 m, so 3 cm of sag is a column still
  // in contact) and at no interface does the load above overhang its
  // support by half a width (0.5 m), where it would tip. Measured after
  // every clipped point was kept inside both boxes: 1.9 cm of sag, the top
  // box 34 cm off the axis and a largest overhang of 18 cm (7.9 cm of sway
  // before, when a vertex outside the lower box was still kept as a
  // contact point; docs/collision-narrow-phase.md).
  WorldSettings settings;
  settings.sleeping = false;
  settings.methods.maxVelocityIterations = settings.velocityIterations;
  settings.methods.blockSolver = false;
  settings.methods.frictionSolve =
      FrictionSolve::PerPoint;                 // the write-up's rows (the coupled block needs the block)
  settings.methods.speculativeMotion = false;  // and its fixed speculative margin
  settings.methods.positionCorrection = PositionCorrection::Baumgarte;
  // ... and its narrow phase every step, as in the talus-writeup backend.
  // This column is marginal: with manifold reuse on it sways 14 cm at a
  // 0.1 mm reuse distance and falls at 1 mm (measured), while the default
  // block solver keeps it within 1 mm with reuse (the test above).
  settings.methods.narrowPhase.reuseDistance = 0.0;
  // ... and its order: pair after pair up the column. Row by row in the
  // coloured order (every other contact, then the rest) the load climbs
  // the column half as fast per sweep and this marginal column falls
  // (measured: 9 m); with the block solver (the default) both orders hold
  // it (the test above).
  settings.methods.contactOrder = ContactOrder::PairByPair;
  const ColumnDeviation writeUp = RunColumn(settings);
  EXPECT_LT(writeUp.vertical, 3e-2);
  EXPECT_LT(writeUp.overhang, 0.5);
}

TEST(WorldPhysics, WarmStartedRestingColumnStopsAtTheLeastSweeps) {
  // New contacts take extra sweeps; once warm started, the column converges
  // within the minimum, so the adaptive count costs nothing at rest.
  WorldSettings settings;
  settings.sleeping = false;
  World world = MakeWorld(settings);
  AddGround(world);
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                  .position = {0, i + 0.5, 0},
                                  .shape = Box(Vec3::Constant(0.5)),
                                  .density = 1000.0}));
  }
  const StepStatistics first = world.Step(kH).Value();
  EXPECT_GT(first.velocitySweeps, settings.velocityIterations);
  EXPECT_LE(first.velocitySweeps, settings.methods.maxVelocityIterations);
  StepStatistics last;
  for (int n = 0; n < 120; ++n) last = world.Step(kH).Value();
  EXPECT_EQ(last.velocitySweeps, settings.velocityIterations);
}

TEST(WorldPhysics, MassComesFromShapeAndDensity) {
  World world;
  const BodyId id =
      world.CreateBody({.type = BodyType::Dynamic, .shape = Box({0.5, 1.0, 1.5}), .density = 2.0}).Value();
  const BodyState s = world.GetBodyState(id).Value();
  // m = rho * 1 * 2 * 3 = 12 kg; Ixx = m (2^2 + 3^2) / 12 = 13 kg m^2.
  EXPECT_NEAR(s.mass, 12.0, 1e-12);
  EXPECT_NEAR(s.localInertia(0, 0), 13.0, 1e-12);
  EXPECT_NEAR(s.localInertia(1, 1), 10.0, 1e-12);
  EXPECT_NEAR(s.localInertia(2, 2), 5.0, 1e-12);
  EXPECT_FALSE(world.CreateBody({.type = BodyType::Dynamic, .shape = Box({1, 1, 1}), .density = -1.0}));
}

TEST(WorldPhysics, SlidingBoxStopsAtTheCoulombDistance) {
  WorldSettings settings;
  settings.sleeping = false;
  World world = MakeWorld(settings);
  AddGround(world, 0.5);
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 0.5, 0},
                                      .linearVelocity = {5, 0, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 500.0,
                                      .friction = 0.5})
                         .Value();
  const double h = 1.0 / 120.0;
  for (int n = 0; n < 1000 && world.GetBodyState(box).Value().linearVelocity.x() > 1e-4; ++n) {
    ASSERT_TRUE(world.Step(h));
  }
  const double expected = 25.0 / (2.0 * 0.5 * kG);
  // 2% (the discrete scheme stops v0 h / 2 = 2 cm short, 0.8%).
  EXPECT_NEAR(world.GetBodyState(box).Value().position.x(), expected, 0.02 * expected);
}

TEST(WorldPhysics, DroppedBoxReboundsToRestitutionSquaredOfItsHeight) {
  WorldSettings settings;
  settings.sleeping = false;
  World world = MakeWorld(settings);
  AddGround(world, 0.5, 0.6);
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 1.5, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 500.0,
                                      .restitution = 0.6})
                         .Value();
  bool bounced = false;
  double apex = 0.0;
  for (int n = 0; n < 960; ++n) {
    ASSERT_TRUE(world.Step(1.0 / 240.0));
    const BodyState s = world.GetBodyState(box).Value();
    if (s.linearVelocity.y() > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, s.position.y() - 0.5);
      if (s.linearVelocity.y() < 0.0) break;
    }
  }
  // Drop 1 m, e = 0.6: 0.36 m, within symplectic Euler's flight lag and
  // the v h contact-finding error (2 cm); measured 0.3512 m with the
  // bounce timed inside the step (tests/dynamics/bounce_timing_test.cpp
  // has the exact translation's 0.5%).
  EXPECT_NEAR(apex, 0.36, 0.02);
}

TEST(WorldPhysics, RestingStackFallsAsleepAndStopsCosting) {
  World world;  // sleeping on by default
  AddGround(world);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                  .position = {0, i + 0.5, 0},
                                  .shape = Box(Vec3::Constant(0.5)),
                                  .density = 1000.0}));
  }
  StepStatistics last;
  for (int n = 0; n < 180; ++n) last = world.Step(kH).Value();
  EXPECT_EQ(last.sleepingBodies, 3);
  EXPECT_EQ(last.awakeBodies, 0);
  EXPECT_EQ(last.contactPoints, 0);
  EXPECT_EQ(last.narrowPhase.pairsTested, 0u);
  EXPECT_EQ(last.islands, 0);
  EXPECT_GE(last.sleepingPairsSkipped, 3);
}

TEST(WorldPhysics, SleepingStackWakesWhenHitAndWhenPushed) {
  World world;
  AddGround(world);
  const BodyId bottom = world
                            .CreateBody({.type = BodyType::Dynamic,
                                         .position = {0, 0.5, 0},
                                         .shape = Box(Vec3::Constant(0.5)),
                                         .density = 1000.0})
                            .Value();
  const BodyId top = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 1.5, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 1000.0})
                         .Value();
  for (int n = 0; n < 180; ++n) ASSERT_TRUE(world.Step(kH));
  ASSERT_FALSE(world.GetBodyState(bottom).Value().awake);
  // A force wakes the body at once and its island at the next pass.
  ASSERT_TRUE(world.ApplyForceToCenter(bottom, {1, 0, 0}));
  EXPECT_TRUE(world.GetBodyState(bottom).Value().awake);
  ASSERT_TRUE(world.Step(kH));
  EXPECT_TRUE(world.GetBodyState(top).Value().awake);
  for (int n = 0; n < 180; ++n) ASSERT_TRUE(world.Step(kH));
  ASSERT_FALSE(world.GetBodyState(top).Value().awake);
  // A falling box landing on the sleeping stack wakes it.
  const BodyId falling = world
                             .CreateBody({.type = BodyType::Dynamic,
                                          .position = {0, 3.5, 0},
                                          .shape = Box(Vec3::Constant(0.5)),
                                          .density = 1000.0})
                             .Value();
  bool woke = false;
  for (int n = 0; n < 60 && !woke; ++n) {
    ASSERT_TRUE(world.Step(kH));
    woke = world.GetBodyState(top).Value().awake && world.GetBodyState(bottom).Value().awake;
  }
  EXPECT_TRUE(woke);
  EXPECT_TRUE(world.IsValid(falling));
}

TEST(WorldPhysics, MovingKinematicBodyWakesAndPushesASleepingBody) {
  World world;
  AddGround(world);
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 0.5, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 1000.0})
                         .Value();
  for (int n = 0; n < 120; ++n) ASSERT_TRUE(world.Step(kH));
  ASSERT_FALSE(world.GetBodyState(box).Value().awake);
  // A kinematic pusher sliding in along +x at 1 m/s from 0.5 m away.
  ASSERT_TRUE(world.CreateBody({.type = BodyType::Kinematic,
                                .position = {-1.5, 0.5, 0},
                                .linearVelocity = {1, 0, 0},
                                .shape = Box({0.5, 0.4, 0.5})}));
  for (int n = 0; n < 60; ++n) ASSERT_TRUE(world.Step(kH));
  const BodyState s = world.GetBodyState(box).Value();
  EXPECT_TRUE(s.awake);
  // Pushed along: after 1 s the pusher's face is at x = 0, so the box's
  // centre is near 0.5 m.
  EXPECT_GT(s.position.x(), 0.4);
}

TEST(WorldPhysics, StaticPairsAndFrictionlessContactsCostNothing) {
  WorldSettings settings;
  settings.sleeping = false;
  World world = MakeWorld(settings);
  AddGround(world, 0.0);
  ASSERT_TRUE(world.CreateBody(
      {.type = BodyType::Static, .position = {3, 0.5, 0}, .shape = Box(Vec3::Constant(0.5))}));
  ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {0, 0.5, 0},
                                .shape = Box(Vec3::Constant(0.5)),
                                .density = 1000.0,
                                .friction = 0.0}));
  const StepStatistics stats = world.Step(kH).Value();
  // The static block on the static ground is never tested.
  EXPECT_EQ(stats.spherePairs, 1);
  EXPECT_EQ(stats.narrowPhase.pairsTested, 1u);
  EXPECT_GT(stats.contactPoints, 0);
  EXPECT_EQ(stats.frictionRows, 0);
  EXPECT_EQ(stats.frictionRowsSkipped, 2 * stats.contactPoints);
  EXPECT_EQ(stats.restitutionSkipped, stats.contactPoints);
}

// FNV-1a over the bits of every body's state.
std::uint64_t HashWorld(const World& world) {
  std::uint64_t hash = 1469598103934665603ull;
  const auto mix = [&hash](const double* values, int count) {
    for (int i = 0; i < count; ++i) {
      unsigned char bytes[sizeof(double)];
      std::memcpy(bytes, &values[i], sizeof(double));
      for (const unsigned char byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
    }
  };
  for (const BodyId id : world.BodyIds()) {
    const BodyState s = world.GetBodyState(id).Value();
    mix(s.position.data(), 3);
    mix(s.orientation.coeffs().data(), 4);
    mix(s.linearVelocity.data(), 3);
    mix(s.angularVelocity.data(), 3);
  }
  return hash;
}

std::uint64_t RunPile(RotationIntegrator rotation, TranslationIntegrator translation) {
  WorldSettings settings;
  settings.methods.rotation = rotation;
  settings.methods.translation = translation;
  World world = MakeWorld(settings);
  AddGround(world);
  for (int i = 0; i < 12; ++i) {
    const double angle = 0.37 * i;
    EXPECT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                  .position = {0.3 * std::sin(angle), 1.0 + 0.9 * i, 0.3 * std::cos(angle)},
                                  .orientation = Quat(Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized())),
                                  .angularVelocity = {0.5, -1.0, 0.2 * i},
                                  .shape = Box({0.4, 0.3, 0.2}),
                                  .density = 700.0,
                                  .restitution = 0.2}));
  }
  for (int n = 0; n < 240; ++n) EXPECT_TRUE(world.Step(kH));
  return HashWorld(world);
}

TEST(WorldPhysics, SameWorldSteppedTwiceFromScratchIsBitIdentical) {
  // The write-up's integrators, then the defaults.
  EXPECT_EQ(RunPile(RotationIntegrator::ConstantRate, TranslationIntegrator::SymplecticEuler),
            RunPile(RotationIntegrator::ConstantRate, TranslationIntegrator::SymplecticEuler));
  EXPECT_EQ(RunPile(WorldSettings{}.methods.rotation, WorldSettings{}.methods.translation),
            RunPile(WorldSettings{}.methods.rotation, WorldSettings{}.methods.translation));
}

TEST(WorldPhysics, DestroyingASupportWakesWhatRestedOnIt) {
  World world;
  const BodyId ground = AddGround(world);
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 0.5, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 1000.0})
                         .Value();
  for (int n = 0; n < 180; ++n) ASSERT_TRUE(world.Step(kH));
  ASSERT_FALSE(world.GetBodyState(box).Value().awake);
  ASSERT_TRUE(world.DestroyBody(ground));
  EXPECT_TRUE(world.GetBodyState(box).Value().awake);
  for (int n = 0; n < 30; ++n) ASSERT_TRUE(world.Step(kH));
  EXPECT_LT(world.GetBodyState(box).Value().position.y(), 0.0);
}

}  // namespace world_physics_test
}  // namespace talus
