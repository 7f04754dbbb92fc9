// The contact solver on analytic manifolds (box corners against planes):
// resting, Coulomb friction stop distances and inclines, restitution,
// energy, the split-impulse option, the skip counters and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "contact_scene.h"

namespace talus {
namespace contact_solver_test {

using testing::ContactScene;
using testing::GroundPlane;

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

WorldSettings Settings() { return WorldSettings{.gravity = {0.0, -kG, 0.0}, .sleeping = false}; }

TEST(ContactSolver, BoxRestsOnGroundWithoutSinking) {
  ContactScene scene(Settings());
  scene.AddPlane({});
  const int box = scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), 3.0);
  for (int n = 0; n < 120; ++n) scene.Step(kH);
  const double settled = scene.Body(box).center.y();
  for (int n = 0; n < 480; ++n) scene.Step(kH);
  const BodySim& b = scene.Body(box);
  // Baumgarte leaves at most `slop` (4 mm) of penetration by design; the
  // box must sit there and stay: no sinking, no creeping, no spin.
  EXPECT_GT(b.center.y(), 0.5 - Settings().slop - 1e-4);
  EXPECT_LT(b.center.y(), 0.5 + 1e-9);
  EXPECT_NEAR(b.center.y(), settled, 1e-6);
  EXPECT_LT(b.linearVelocity.norm(), 1e-6);
  EXPECT_LT(b.angularVelocity.norm(), 1e-6);
}

// Slides a box at v0 along x and returns the distance it travels until its
// velocity first reaches zero.
double StopDistance(double v0, double mu, const WorldSettings& settings, double h) {
  ContactScene scene(settings);
  scene.AddPlane({.friction = mu});
  const int box = scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), 2.0, Quat::Identity(), mu);
  scene.Body(box).linearVelocity = Vec3(v0, 0, 0);
  // Stopped means below 0.1 mm/s: without warm starting, ten Gauss-Seidel
  // sweeps leave a residual creep of a few um/s once static (measured
  // 3.6e-6 m/s), which is the solver's convergence, not sliding.
  int n = 0;
  for (; n < 5000 && scene.Body(box).linearVelocity.x() > 1e-4; ++n) scene.Step(h);
  EXPECT_LT(n, 5000) << "did not stop";
  // Friction at the base tips the box forward a little while it slides; it
  // rocks back when it stops, hence a millimetre per second of slack.
  EXPECT_LT(scene.Body(box).linearVelocity.norm(), 1e-3);
  return scene.Body(box).center.x();
}

// The discrete scheme takes mu g h off the speed every step and moves with
// the new speed, so it stops v0 h / 2 short of v0^2 / (2 mu g); at 120 Hz
// that is at most 1.3% of the distance for the cases below, inside the 2%.
constexpr double kSlideH = 1.0 / 120.0;

TEST(ContactSolver, SlidingBoxStopsAtTheCoulombDistance) {
  for (const double mu : {0.2, 0.5, 0.8}) {
    const double v0 = 5.0;
    const double expected = v0 * v0 / (2.0 * mu * kG);
    EXPECT_NEAR(StopDistance(v0, mu, Settings(), kSlideH), expected, 0.02 * expected) << "mu " << mu;
  }
}

TEST(ContactSolver, SlidingBoxFollowsTheDiscreteFrictionRecurrence) {
  // At 60 Hz the 2% bound is too tight for the continuous answer, but the
  // discrete one, v0^2 / (2 mu g) - v0 h / 2, holds to a fraction of a step.
  const double v0 = 5.0, mu = 0.8, h = 1.0 / 60.0;
  const double expected = v0 * v0 / (2.0 * mu * kG) - 0.5 * v0 * h;
  EXPECT_NEAR(StopDistance(v0, mu, Settings(), h), expected, v0 * h / 4.0);
}

TEST(ContactSolver, StopDistanceHoldsWithoutWarmStartingAndWithSplitImpulses) {
  const double expected = 25.0 / (2.0 * 0.5 * kG);
  WorldSettings cold = Settings();
  cold.methods.warmStarting = false;
  EXPECT_NEAR(StopDistance(5.0, 0.5, cold, kSlideH), expected, 0.02 * expected);
  WorldSettings split = Settings();
  split.methods.positionCorrection = PositionCorrection::SplitImpulses;
  EXPECT_NEAR(StopDistance(5.0, 0.5, split, kSlideH), expected, 0.02 * expected);
}

// A unit box resting on a plane tilted by `theta` about z, downhill along
// +x; returns its displacement along the slope after each of two times.
struct InclineRun {
  double displacement1 = 0.0, displacement2 = 0.0;
  double speed1 = 0.0, speed2 = 0.0;
};

InclineRun RunIncline(double theta, double mu, double t1, double t2) {
  ContactScene scene(Settings());
  const Vec3 normal(std::sin(theta), std::cos(theta), 0.0);
  const Vec3 downhill(std::cos(theta), -std::sin(theta), 0.0);
  scene.AddPlane({.normal = normal, .friction = mu});
  const Quat tilt(Eigen::AngleAxisd(-theta, Vec3::UnitZ()));
  const Vec3 start = 0.5 * normal;
  const int box = scene.AddBox(start, Vec3::Constant(0.5), 1.0, tilt, mu);
  InclineRun run;
  const int n1 = static_cast<int>(std::lround(t1 / kH));
  const int n2 = static_cast<int>(std::lround(t2 / kH));
  for (int n = 1; n <= n2; ++n) {
    scene.Step(kH);
    const BodySim& b = scene.Body(box);
    if (n == n1) {
      run.displacement1 = (b.center - start).dot(downhill);
      run.speed1 = b.linearVelocity.dot(downhill);
    }
    if (n == n2) {
      run.displacement2 = (b.center - start).dot(downhill);
      run.speed2 = b.linearVelocity.dot(downhill);
    }
  }
  return run;
}

TEST(ContactSolver, BoxOnInclineStaysPutWhenTanThetaBelowMu) {
  const double theta = 20.0 * std::numbers::pi / 180.0;  // tan = 0.36
  const InclineRun run = RunIncline(theta, 0.5, 1.0, 3.0);
  // Static friction holds: no creep between 1 s and 3 s beyond 0.1 mm.
  EXPECT_LT(std::abs(run.displacement2), 1e-3);
  EXPECT_LT(std::abs(run.displacement2 - run.displacement1), 1e-4);
  EXPECT_LT(std::abs(run.speed2), 1e-4);
}

TEST(ContactSolver, BoxOnInclineSlidesAtCoulombAcceleration) {
  const double theta = 30.0 * std::numbers::pi / 180.0;
  for (const double mu : {0.0, 0.2, 0.4}) {
    const InclineRun run = RunIncline(theta, mu, 0.5, 1.5);
    const double expected = kG * (std::sin(theta) - mu * std::cos(theta));
    const double measured = (run.speed2 - run.speed1) / 1.0;
    // The spec asks for 2%; on a flat face with warm starting the solver
    // reproduces g (sin - mu cos) to round-off (measured 3e-15), so any
    // drift beyond 1e-6 is a regression.
    EXPECT_NEAR(measured, expected, 1e-6 * expected) << "mu " << mu;
  }
}

// Drops a flat box from `height` (bottom face above the ground) and returns
// the highest the bottom face gets after the first bounce.
double ReboundHeight(double height, double e, double h) {
  ContactScene scene(Settings());
  scene.AddPlane({.friction = 0.5, .restitution = e});
  const int box = scene.AddBox({0, 0.5 + height, 0}, Vec3::Constant(0.5), 1.0, Quat::Identity(), 0.5, e);
  bool bounced = false;
  double apex = 0.0;
  for (int n = 0; n < static_cast<int>(4.0 / h); ++n) {
    scene.Step(h);
    const BodySim& b = scene.Body(box);
    if (!bounced && b.linearVelocity.y() > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.center.y() - 0.5);
      if (b.linearVelocity.y() < 0.0) break;
    }
  }
  return apex;
}

TEST(ContactSolver, DroppedBoxReboundsToRestitutionSquaredOfItsHeight) {
  const double height = 1.0;
  for (const double e : {0.3, 0.6, 0.9}) {
    // At 240 Hz symplectic Euler's flights lag the parabola (a flight that
    // leaves at u peaks about u h / 2 = 9 mm low for u = 4.4 m/s), and with
    // bounces at the step's boundary the contact is found within v h =
    // 1.8 cm of the surface, so the apex carries an error of that order;
    // measured 0.0865, 0.3513, 0.7944 m with bounces timed inside the step
    // (the default), 0.0915, 0.3675, 0.8257 m at the step's boundary,
    // against 0.09, 0.36, 0.81 m.
    EXPECT_NEAR(ReboundHeight(height, e, 1.0 / 240.0), e * e * height, 0.02) << "e " << e;
  }
  EXPECT_LT(ReboundHeight(height, 0.0, 1.0 / 240.0), 0.01);
}

// A tumbling cube in a closed room of six frictionless, inelastic walls.
// With split impulses position correction cannot add energy; contacts with
// e = 0 only remove it; symplectic Euler under gravity loses g^2 h^2 / 2 per
// step; the cube's isotropic inertia keeps rotational energy constant in
// free flight. So total energy never grows.
void RunClosedRoom(const WorldSettings& settings, int steps, std::vector<double>* energies) {
  // A 0.3 m speculative margin (> the largest v h, 0.15 m) finds every
  // impact before it penetrates: nothing for position correction to undo.
  ContactScene scene(settings, 0.3);
  const double half = 1.5;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Vec3 n = Vec3::Zero();
      n[axis] = sign;
      scene.AddPlane({.normal = n, .offset = -half, .friction = 0.0});
    }
  }
  const int box = scene.AddBox({0.2, 0.4, -0.1}, Vec3::Constant(0.25), 1.0,
                               Quat(Eigen::AngleAxisd(0.8, Vec3(1, 2, 3).normalized())), 0.0, 0.0);
  scene.Body(box).linearVelocity = Vec3(3.0, -2.0, 4.0);
  scene.Body(box).angularVelocity = Vec3(5.0, -3.0, 2.0);
  for (int n = 0; n < steps; ++n) {
    scene.Step(kH);
    energies->push_back(scene.Energy());
  }
}

TEST(ContactSolver, FrictionlessInelasticClosedSystemNeverGainsEnergy) {
  WorldSettings settings = Settings();
  settings.methods.positionCorrection = PositionCorrection::SplitImpulses;
  for (const bool warm : {false, true}) {
    settings.methods.warmStarting = warm;
    std::vector<double> energies;
    RunClosedRoom(settings, 600, &energies);
    for (std::size_t n = 1; n < energies.size(); ++n) {
      // Round-off on energies of ~30 J.
      EXPECT_LE(energies[n], energies[n - 1] + 1e-9) << "step " << n << " warm " << warm;
    }
    EXPECT_LT(energies.back(), energies.front());
  }
}

TEST(ContactSolver, SplitImpulsesPushOutWithoutLaunching) {
  // A box started 5 cm deep: Baumgarte's bias turns the correction into
  // upward velocity (the box pops); split impulses move it out with
  // pseudo-velocities and leave its real velocity near zero.
  const auto peakUpwardSpeed = [](bool split) {
    WorldSettings settings = Settings();
    settings.methods.positionCorrection =
        split ? PositionCorrection::SplitImpulses : PositionCorrection::Baumgarte;
    ContactScene scene(settings);
    scene.AddPlane({});
    const int box = scene.AddBox({0, 0.45, 0}, Vec3::Constant(0.5), 1.0);
    double peak = 0.0;
    for (int n = 0; n < 120; ++n) {
      scene.Step(kH);
      peak = std::max(peak, scene.Body(box).linearVelocity.y());
    }
    EXPECT_GT(scene.Body(box).center.y(), 0.5 - 0.006) << "split " << split;
    return peak;
  };
  EXPECT_GT(peakUpwardSpeed(false), 0.3);
  EXPECT_LT(peakUpwardSpeed(true), 1e-3);
}

TEST(ContactSolver, BlockSolvedCornersOfAColdBoxShareTheLoadEvenly) {
  // A box landing flat: row by row the first corner takes more of the
  // impulse and the box starts to spin; the 4-point block gives each corner
  // a quarter. Round-off tolerance on impulses of ~0.16 N s.
  for (const bool block : {false, true}) {
    WorldSettings settings = Settings();
    settings.methods.blockSolver = block;
    settings.methods.maxVelocityIterations = 1;
    settings.velocityIterations = 1;
    ContactScene scene(settings);
    scene.AddPlane({});
    const int box = scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), 1.0);
    scene.Step(kH);
    const double spin = scene.Body(box).angularVelocity.norm();
    if (block) {
      EXPECT_LT(spin, 1e-12);
    } else {
      EXPECT_GT(spin, 1e-3);
    }
  }
}

TEST(ContactSolver, FrictionlessContactsBuildNoFrictionRows) {
  ContactScene scene(Settings());
  scene.AddPlane({.friction = 0.0});
  scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), 1.0, Quat::Identity(), 0.0);
  scene.Step(kH);
  EXPECT_EQ(scene.LastStats().contactPoints, 4);
  EXPECT_EQ(scene.LastStats().frictionRows, 0);
  EXPECT_EQ(scene.LastStats().frictionRowsSkipped, 8);
  EXPECT_EQ(scene.LastStats().restitutionSkipped, 4);
}

TEST(ContactSolver, FrictionAndRestitutionRowsAreBuiltWhenUsed) {
  ContactScene scene(Settings());
  scene.AddPlane({.friction = 0.5, .restitution = 0.5});
  scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), 1.0);
  scene.Step(kH);
  // The default (Adaptive) gives a lightly loaded face the manifold's three
  // rows; per point it would be eight.
  EXPECT_EQ(scene.LastStats().frictionRows, 3);
  EXPECT_EQ(scene.LastStats().frictionRowsSkipped, 0);
  EXPECT_EQ(scene.LastStats().restitutionSkipped, 0);
  scene.Step(kH);
  // Same corners touching: every point finds last step's impulses.
  EXPECT_EQ(scene.LastStats().warmStartedPoints, 4);
}

TEST(ContactSolver, CarryImpulsesMatchesPointsByFeatureIdInAnyOrder) {
  ContactManifold before{};
  before.normal = Vec3::UnitY();
  before.pointCount = 3;
  for (int i = 0; i < 3; ++i) {
    before.points[static_cast<std::size_t>(i)] = {Vec3(i, 0, 0), 0.0, 10u + static_cast<std::uint32_t>(i)};
  }
  Contact old = MakeContact(1, 0, before, 0.5, 0.0);
  old.normalImpulse = {1.0, 2.0, 3.0};
  old.frictionImpulse[2] = Vec3(0.5, 0, 0);
  ContactManifold after = before;
  after.points[0] = {Vec3(2, 0, 0), 0.0, 12};  // was point 2
  after.points[1] = {Vec3(7, 0, 0), 0.0, 99};  // a new feature far from every old point
  after.points[2] = {Vec3(0, 0, 0), 0.0, 10};  // was point 0
  Contact fresh = MakeContact(1, 0, after, 0.5, 0.0);
  Contact otherPair = MakeContact(2, 0, before, 0.5, 0.0);
  std::vector<Contact> previous = {old};
  std::vector<Contact> current = {fresh, otherPair};
  EXPECT_EQ(CarryImpulses(previous, current), 2);
  EXPECT_EQ(current[0].normalImpulse[0], 3.0);
  EXPECT_EQ(current[0].frictionImpulse[0], Vec3(0.5, 0, 0));
  EXPECT_EQ(current[0].normalImpulse[1], 0.0);
  EXPECT_EQ(current[0].normalImpulse[2], 1.0);
  EXPECT_EQ(current[1].normalImpulse[0], 0.0);
}

TEST(ContactSolver, CarryImpulsesFallsBackToTheNearestOldPointWhenIdsChange) {
  ContactManifold before{};
  before.normal = Vec3::UnitY();
  before.pointCount = 2;
  before.points[0] = {Vec3(0, 0, 0), 0.0, 1};
  before.points[1] = {Vec3(1, 0, 0), 0.0, 2};
  Contact old = MakeContact(1, 0, before, 0.5, 0.0);
  old.normalImpulse = {4.0, 5.0};
  ContactManifold after = before;
  // Renamed (the narrow phase swapped reference faces) but within the 1 cm
  // match distance of the old points; the third is new and too far.
  after.pointCount = 3;
  after.points[0] = {Vec3(1.004, 0, 0), 0.0, 77};
  after.points[1] = {Vec3(0.003, 0, 0), 0.0, 78};
  after.points[2] = {Vec3(0.5, 0, 0), 0.0, 79};
  std::vector<Contact> previous = {old};
  std::vector<Contact> current = {MakeContact(1, 0, after, 0.5, 0.0)};
  EXPECT_EQ(CarryImpulses(previous, current), 2);
  EXPECT_EQ(current[0].normalImpulse[0], 5.0);
  EXPECT_EQ(current[0].normalImpulse[1], 4.0);
  EXPECT_EQ(current[0].normalImpulse[2], 0.0);
}

TEST(ContactSolver, CombineRulesMatchTheirDefinitions) {
  EXPECT_DOUBLE_EQ(MixFriction(0.25, 0.64, FrictionCombine::GeometricMean), 0.4);
  EXPECT_DOUBLE_EQ(MixFriction(0.25, 0.64, FrictionCombine::Product), 0.16);
  EXPECT_DOUBLE_EQ(MixFriction(0.25, 0.64, FrictionCombine::Min), 0.25);
  EXPECT_DOUBLE_EQ(MixFriction(0.25, 0.64, FrictionCombine::Max), 0.64);
  EXPECT_DOUBLE_EQ(MixFriction(0.25, 0.64, FrictionCombine::Average), 0.445);
  EXPECT_DOUBLE_EQ(MixRestitution(0.2, 0.5, RestitutionCombine::Max), 0.5);
  EXPECT_DOUBLE_EQ(MixRestitution(0.2, 0.5, RestitutionCombine::Product), 0.1);
  EXPECT_DOUBLE_EQ(MixRestitution(0.2, 0.5, RestitutionCombine::Min), 0.2);
  EXPECT_DOUBLE_EQ(MixRestitution(0.2, 0.5, RestitutionCombine::Average), 0.35);
}

// FNV-1a over the bytes of every body's state.
std::uint64_t HashBodies(ContactScene& scene, int bodyCount) {
  std::uint64_t hash = 1469598103934665603ull;
  const auto mix = [&hash](const double* values, int count) {
    unsigned char bytes[sizeof(double)];
    for (int i = 0; i < count; ++i) {
      std::memcpy(bytes, &values[i], sizeof(double));
      for (const unsigned char byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
    }
  };
  for (int i = 0; i < bodyCount; ++i) {
    const BodySim& b = scene.Body(i);
    mix(b.center.data(), 3);
    mix(b.orientation.coeffs().data(), 4);
    mix(b.linearVelocity.data(), 3);
    mix(b.angularVelocity.data(), 3);
  }
  return hash;
}

TEST(ContactSolver, SameSceneSteppedTwiceGivesBitIdenticalStates) {
  const auto run = [] {
    WorldSettings settings = Settings();
    settings.methods.rotation = RotationIntegrator::MomentumSplitting;
    settings.methods.translation = TranslationIntegrator::ExactConstantAcceleration;
    ContactScene scene(settings);
    scene.AddPlane({});
    scene.AddPlane({.normal = Vec3(-1, 0, 0), .offset = -2.0});
    const int box = scene.AddBox({0.3, 2.0, 0.1}, Vec3(0.5, 0.3, 0.2), 1.5,
                                 Quat(Eigen::AngleAxisd(0.6, Vec3(1, 1, 0).normalized())), 0.6, 0.4);
    scene.Body(box).linearVelocity = Vec3(2.0, 0.0, 0.5);
    scene.Body(box).angularVelocity = Vec3(1.0, 4.0, -2.0);
    for (int n = 0; n < 300; ++n) scene.Step(kH);
    return HashBodies(scene, 3);
  };
  const std::uint64_t first = run();
  EXPECT_EQ(first, run());
}

}  // namespace contact_solver_test
}  // namespace talus
