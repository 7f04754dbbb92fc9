// FrictionSolve::CoupledBlock through the World: a sticking pair's normals and
// friction solved as one block. Analytic answers first (the discrete Coulomb
// stop distance, a box held on a slope, a box sliding down one), then the
// property that matters for trusting it (it converges to what the per-point
// rows converge to), then refusals and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "contact_scene.h"
#include "friction_scenes.h"
#include "talus/world.h"

namespace talus {
namespace coupled_block_test {

using namespace friction_scenes;  // NOLINT(google-build-using-namespace): the shared scenes

TEST(CoupledBlock, BoxStoppingAtThirtyHertzWithFiveSweepsStopsAtTheDiscreteCoulombDistance) {
  const double h = 1.0 / 30.0;
  const double expected = DiscreteStopDistance(3.0, 0.5, h);
  const Stop coupled = SlideAndStop(Settings(FrictionSolve::CoupledBlock, 5), 3.0, 0.5, h);
  // 1e-9 m: the scale of the testbed's input perturbation; the round-off of
  // eighteen steps' sums is 1e-15 m. At rest means no velocity above
  // round-off: the block leaves a sticking pair exactly solved.
  EXPECT_NEAR(coupled.distance, expected, 1e-9);
  EXPECT_LT(coupled.lateral, 1e-9);
  EXPECT_LT(coupled.restSpeed, 1e-9);
  // The scene tells the two apart: row by row, each friction impulse tilts
  // the cube and the normals undo it, so five sweeps leave the stopping
  // step unconverged (measured 2.6e-5 m off, then rocking at 1e-3 m/s).
  const Stop perPoint = SlideAndStop(Settings(FrictionSolve::PerPoint, 5), 3.0, 0.5, h);
  EXPECT_GT(std::abs(perPoint.distance - expected), 1e-6);
}

// At 1/120 s the answer is not exact yet, for a reason outside the solver:
// the cube slows below the manifold reuse distance (0.16 mm a step against
// 0.5 mm), the reused points are the midpoints of surface points that slid
// apart, so they lag the cube by half the slide and turn it slightly; the
// cube then stands on three points and the stopping block is refused
// (measured mu 0.3, v0 1: 3.2e-6 m off; exact with reuse off). Refusing
// reuse to sliding pairs fixes it but cost the 1000-hull pile 65% more
// narrow phase, so it is left for the reuse rebuild (docs/dynamics.md).
TEST(CoupledBlock, StopDistanceIsExactOverFrictionSpeedAndStep) {
  for (const double mu : {0.3, 0.5, 0.8}) {
    for (const double v0 : {1.0, 3.0}) {
      for (const double h : {1.0 / 30.0, 1.0 / 60.0}) {
        const Stop stop = SlideAndStop(Settings(FrictionSolve::CoupledBlock, 5), v0, mu, h);
        // As above; mu 0.8 stops a 1 m/s box in 4 steps at 30 Hz.
        EXPECT_NEAR(stop.distance, DiscreteStopDistance(v0, mu, h), 1e-9)
            << "mu " << mu << " v0 " << v0 << " h " << h;
        EXPECT_LT(stop.restSpeed, 1e-9) << "mu " << mu << " v0 " << v0 << " h " << h;
      }
    }
  }
}

TEST(CoupledBlock, BoxOnASlopeBelowTheFrictionAngleStaysPut) {
  // tan(20 deg) = 0.36 < mu = 0.5: static friction holds. 1e-9 m in 2 s:
  // the block is accepted every sweep, so nothing creeps beyond round-off.
  const double angle = 20.0 * std::numbers::pi / 180.0;
  EXPECT_LT(
      std::abs(SlopeDisplacement(Settings(FrictionSolve::CoupledBlock, 5), angle, 0.5, 1.0 / 60.0, 120)),
      1e-9);
}

TEST(CoupledBlock, BoxOnASlopeAboveTheFrictionAngleSlidesAtGTimesSinMinusMuCos) {
  // tan(30 deg) = 0.58 > mu = 0.3: the block must be refused every step
  // (the friction it asks for exceeds mu N) and the box slides with
  // a = g (sin - mu cos); moving by h v(n+1), it covers a h^2 n (n + 1) / 2
  // in n steps. 1e-9 relative: round-off of the sums.
  const double angle = 30.0 * std::numbers::pi / 180.0;
  const double h = 1.0 / 60.0;
  const int steps = 60;
  const double a = kG * (std::sin(angle) - 0.3 * std::cos(angle));
  const double expected = a * h * h * steps * (steps + 1) / 2.0;
  const double moved = SlopeDisplacement(Settings(FrictionSolve::CoupledBlock, 5), angle, 0.3, h, steps);
  EXPECT_NEAR(moved, expected, 1e-9 * expected);
}

// Converged, the coupled block and the per-point rows must agree on how the
// bodies move (they may share friction among the points differently; that
// moves nothing). Cubes launched with random slide and spin, on the ground
// and on a wide dynamic slab on the ground (so that both bodies of a pair
// turn), 200 sweeps each way, final poses compared.
TEST(CoupledBlock, ConvergesToWhereThePerPointRowsConverge) {
  unsigned state = 12345u;
  const auto uniform = [&state](double lo, double hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (state >> 8) / double(1u << 24);
  };
  for (int trial = 0; trial < 8; ++trial) {
    const bool onSlab = trial % 2 == 1;
    const Vec3 velocity(uniform(-2, 2), 0, uniform(-2, 2));
    const Vec3 spin(0, uniform(-6, 6), 0);
    const double mu = uniform(0.2, 0.9);
    Vec3 final[2];
    Vec3 slabFinal[2];
    for (int variant = 0; variant < 2; ++variant) {
      WorldSettings settings =
          Settings(variant == 0 ? FrictionSolve::PerPoint : FrictionSolve::CoupledBlock, 200);
      // The sweeps' fixed points are compared: shock propagation's per-point
      // rows after them move both a little (5.3e-6 m apart at trial 4 with it).
      settings.methods.shockPropagation = false;
      World world = World::Create(settings).Value();
      AddGround(world, mu);
      BodyId slab{};
      double base = 0.0;
      if (onSlab) {
        slab = world
                   .CreateBody({.type = BodyType::Dynamic,
                                .position = {0, 0.1, 0},
                                .shape = Box({3, 0.1, 3}),
                                .density = 200.0,
                                .friction = mu})
                   .Value();
        base = 0.2;
      }
      const BodyId box = AddCube(world, {0, base + 0.25, 0}, velocity, spin, mu);
      for (int n = 0; n < 120; ++n) EXPECT_TRUE(world.Step(1.0 / 60.0));
      final[variant] = world.GetBodyState(box).Value().position;
      slabFinal[variant] = onSlab ? world.GetBodyState(slab).Value().position : Vec3::Zero();
    }
    // 1e-6 m: 200 sweeps converge both to 1e-9 m/s or better per step; the
    // stopping step's residual is what is left (measured below 1e-8 m).
    EXPECT_LT((final[0] - final[1]).norm(), 1e-6) << "trial " << trial;
    EXPECT_LT((slabFinal[0] - slabFinal[1]).norm(), 1e-6) << "trial " << trial;
  }
}

// A cube leaving the ground: the block would hold it down with a pulling
// normal impulse, so it must be refused, and the cube flies the parabola
// (no impulse touches it, so it moves exactly under gravity).
TEST(CoupledBlock, ACubeLeavingTheGroundIsNotHeldDown) {
  const double h = 1.0 / 60.0;
  World world = World::Create(Settings(FrictionSolve::CoupledBlock, 10)).Value();
  AddGround(world, 0.8);
  const BodyId box = AddCube(world, {0, 0.25, 0}, {0.5, 1.0, 0}, {0, 2.0, 0}, 0.8);
  for (int n = 1; n <= 10; ++n) {
    EXPECT_TRUE(world.Step(h));
    const double t = n * h;
    const BodyState s = world.GetBodyState(box).Value();
    // 1e-12 m: free flight is exact for constant gravity (round-off only).
    EXPECT_NEAR(s.position.y(), 0.25 + 1.0 * t - 0.5 * kG * t * t, 1e-12) << "step " << n;
    EXPECT_NEAR(s.position.x(), 0.5 * t, 1e-12) << "step " << n;
  }
}

// A cube spinning slowly on the ground: one step's friction torque can stop
// it (the four corners' pyramid bounds give 33 rad/s^2 for mu 0.5; 0.3 rad/s
// needs 18 at 60 Hz), so the stopping step is a sticking block, and one
// sweep must stop it to round-off, spin pattern and all. Both creation
// orders, so the cube is body A of its pair in one and body B in the other.
// Row by row, one sweep leaves it turning.
TEST(CoupledBlock, ASlowSpinStopsInOneSweep) {
  for (const bool cubeFirst : {false, true}) {
    for (const FrictionSolve friction : {FrictionSolve::CoupledBlock, FrictionSolve::PerPoint}) {
      WorldSettings settings = Settings(friction, 1);
      settings.methods.maxVelocityIterations = 1;  // one sweep, no extra sweeps for the new pair
      World world = World::Create(settings).Value();
      if (!cubeFirst) AddGround(world, 0.5);
      const BodyId box = AddCube(world, {0, 0.25, 0}, Vec3::Zero(), {0, 0.3, 0}, 0.5);
      if (cubeFirst) AddGround(world, 0.5);
      EXPECT_TRUE(world.Step(1.0 / 60.0));
      const BodyState s = world.GetBodyState(box).Value();
      const double motion = s.angularVelocity.norm() + s.linearVelocity.norm();
      if (friction == FrictionSolve::CoupledBlock) {
        EXPECT_LT(motion, 1e-12) << "cube first " << cubeFirst;  // round-off of one solve
      } else {
        EXPECT_GT(motion, 1e-6) << "cube first " << cubeFirst;  // the scene tells them apart
      }
    }
  }
}

// The impulses the solver stores (next step's warm start) must be the ones
// that moved the body: by the impulse-momentum theorem, the sum of a step's
// contact impulses is m dv - m g h and their moment about the centre of
// mass is I dw. A cube sliding slowly and spinning on a plane, stopped by
// one sticking block in one sweep, on both sides of the pair. (Four times
// faster it could not stick: the friction's pitch loads one corner with
// 1.5 N s of the 10, which cannot carry its share, and the block is
// rightly refused.)
TEST(CoupledBlock, StoredImpulsesAreTheOnesThatMovedTheBody) {
  for (const bool planeFirst : {true, false}) {
    WorldSettings settings = Settings(FrictionSolve::CoupledBlock, 1);
    settings.methods.maxVelocityIterations = 1;
    settings.gravity = Vec3(0, -kG, 0);
    testing::ContactScene scene(settings);
    const double mass = 62.5;
    int box = -1;
    if (planeFirst) scene.AddPlane({.friction = 0.5});
    box = scene.AddBox({0, 0.25, 0}, Vec3::Constant(0.25), mass, Quat::Identity(), 0.5);
    if (!planeFirst) scene.AddPlane({.friction = 0.5});
    scene.Body(box).linearVelocity = Vec3(0.01, 0, -0.0075);
    scene.Body(box).angularVelocity = Vec3(0, 0.1, 0);
    const Vec3 v0 = scene.Body(box).linearVelocity;
    const Vec3 w0 = scene.Body(box).angularVelocity;
    const Vec3 c0 = scene.Body(box).center;
    const Mat3 inertia = scene.Body(box).invInertiaWorld.inverse();
    const double h = 1.0 / 60.0;
    scene.Step(h);
    const BodySim& after = scene.Body(box);
    const StoredImpulses stored = SumStoredImpulses(scene, box, c0);
    const Vec3& force = stored.force;
    const Vec3& moment = stored.moment;
    ASSERT_EQ(stored.points, 4) << "plane first " << planeFirst;
    // Stopped by the block (1e-12: round-off of one solve) ...
    EXPECT_LT(after.linearVelocity.norm() + after.angularVelocity.norm(), 1e-12)
        << "plane first " << planeFirst;
    // ... and the stored impulses account for it (1e-9 of the weight's
    // impulse m g h = 10 N s, and of I w0 = 0.2 N m s: round-off).
    const Vec3 expectedForce = mass * (after.linearVelocity - v0) - mass * h * settings.gravity;
    EXPECT_LT((force - expectedForce).norm(), 1e-9 * mass * kG * h) << "plane first " << planeFirst;
    const Vec3 expectedMoment = inertia * (after.angularVelocity - w0);
    EXPECT_LT((moment - expectedMoment).norm(), 1e-9 * (inertia * w0).norm()) << "plane first " << planeFirst;
  }
}

// Where the coupled block would do nothing (the coloured solver has none; it
// extends the normal block, which blockSolver = false turns off), the
// settings are refused, naming both settings, instead of silently running
// the per-point rows; with PerPoint the same settings are accepted.
TEST(CoupledBlock, IsRefusedWhereItWouldDoNothingAndOutOfRange) {
  WorldSettings coloured = Settings(FrictionSolve::CoupledBlock, 10);
  coloured.methods.contactOrder = ContactOrder::ByColour;
  const auto refused = World::Create(coloured);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.GetError().message.find("frictionSolve = CoupledBlock"), std::string::npos)
      << refused.GetError().message;
  EXPECT_NE(refused.GetError().message.find("contactOrder = PairByPair"), std::string::npos)
      << refused.GetError().message;
  coloured.methods.frictionSolve = FrictionSolve::PerPoint;
  EXPECT_TRUE(World::Create(coloured));

  WorldSettings rowByRow = Settings(FrictionSolve::CoupledBlock, 10);
  rowByRow.methods.blockSolver = false;
  const auto noBlock = World::Create(rowByRow);
  ASSERT_FALSE(noBlock);
  EXPECT_NE(noBlock.GetError().message.find("frictionSolve = CoupledBlock"), std::string::npos)
      << noBlock.GetError().message;
  EXPECT_NE(noBlock.GetError().message.find("blockSolver"), std::string::npos) << noBlock.GetError().message;
  rowByRow.methods.frictionSolve = FrictionSolve::PerPoint;
  EXPECT_TRUE(World::Create(rowByRow));

  // SetSettings applies the same rule and leaves the world as it was.
  World world = World::Create(Settings(FrictionSolve::CoupledBlock, 10)).Value();
  WorldSettings change = world.Settings();
  change.methods.blockSolver = false;
  EXPECT_FALSE(world.SetSettings(change));
  EXPECT_TRUE(world.Settings().methods.blockSolver);

  WorldSettings unknown = Settings(FrictionSolve::PerPoint, 10);
  unknown.methods.frictionSolve = static_cast<FrictionSolve>(7);
  const auto bad = World::Create(unknown);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.GetError().message.find("WorldSettings.methods.frictionSolve = 7"), std::string::npos)
      << bad.GetError().message;
}

// Sixteen cubes sliding and spinning into each other and to rest: the same
// bits at 1, 2 and 3 threads (Prepare builds the rows on the pool).
TEST(CoupledBlock, BitIdenticalForAnyThreadCount) {
  ExpectSixteenCubesBitIdenticalForAnyThreadCount(Settings(FrictionSolve::CoupledBlock, 10));
}

}  // namespace coupled_block_test
}  // namespace talus
