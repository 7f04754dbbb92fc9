// FrictionSolve::PerManifold: a pair's friction as slip rows at its
// centre of pressure and a spin row. Analytic answers first (the discrete
// Coulomb stop, a box held on a slope and one sliding down it, the spin-down
// of a cube on its four corners), then properties over random launches
// (friction only takes energy; the stored impulses are the ones that moved
// the body; the per-point storage gives the manifold's impulses back), then
// refusals and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "contact_scene.h"
#include "dynamics/manifold_friction.h"
#include "friction_scenes.h"
#include "talus/world.h"

namespace talus {
namespace manifold_friction_test {

using namespace friction_scenes;  // NOLINT(google-build-using-namespace): the shared scenes

WorldSettings Manifold(int iterations) { return Settings(FrictionSolve::PerManifold, iterations); }

// A deterministic uniform draw in [lo, hi).
struct Draw {
  unsigned state;
  double operator()(double lo, double hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (state >> 8) / double(1u << 24);
  }
};

// Friction at the manifold's centre, 0.25 m below the centre of mass,
// pitches the cube and the normal rows take that back over the sweeps, so
// the stopping step is converged only as far as its sweeps go: measured at
// 10 sweeps up to 2.7e-5 m short, at 20 below 2e-7 m. The bounds are
// 1e-4 m and 1e-6 m: a Coulomb bound off by 1% moves the 0.5 m stop by
// 5 mm, and a residual that does not shrink with the sweeps fails the
// second.
TEST(ManifoldFriction, SlidingBoxStopsAtTheDiscreteCoulombDistance) {
  for (const auto& [sweeps, bound] : {std::pair{10, 1e-4}, std::pair{20, 1e-6}}) {
    for (const double mu : {0.3, 0.5, 0.8}) {
      for (const double v0 : {1.0, 3.0}) {
        for (const double h : {1.0 / 30.0, 1.0 / 60.0}) {
          const Stop stop = SlideAndStop(Manifold(sweeps), v0, mu, h);
          EXPECT_NEAR(stop.distance, DiscreteStopDistance(v0, mu, h), bound)
              << "sweeps " << sweeps << " mu " << mu << " v0 " << v0 << " h " << h;
          EXPECT_LT(stop.lateral, 1e-9) << "sweeps " << sweeps << " mu " << mu << " v0 " << v0;
          EXPECT_LT(stop.restSpeed, 1e-6) << "sweeps " << sweeps << " mu " << mu << " v0 " << v0;
        }
      }
    }
  }
}

TEST(ManifoldFriction, BoxOnASlopeBelowTheFrictionAngleStaysPut) {
  // tan(20 deg) = 0.36 < mu = 0.5: static friction holds. 1e-6 m in 2 s
  // (the testbed's rest truths allow 1 mm).
  const double angle = 20.0 * std::numbers::pi / 180.0;
  EXPECT_LT(std::abs(SlopeDisplacement(Manifold(10), angle, 0.5, 1.0 / 60.0, 120)), 1e-6);
}

TEST(ManifoldFriction, BoxOnASlopeAboveTheFrictionAngleSlidesAtGTimesSinMinusMuCos) {
  // tan(30 deg) = 0.58 > mu = 0.3: the slip row is clamped to mu N every
  // step and the box slides with a = g (sin - mu cos), covering
  // a h^2 n (n + 1) / 2 in n steps. 1e-9 relative: round-off of the sums.
  const double angle = 30.0 * std::numbers::pi / 180.0;
  const double h = 1.0 / 60.0;
  const int steps = 60;
  const double a = kG * (std::sin(angle) - 0.3 * std::cos(angle));
  const double expected = a * h * h * steps * (steps + 1) / 2.0;
  EXPECT_NEAR(SlopeDisplacement(Manifold(10), angle, 0.3, h, steps), expected, 1e-9 * expected);
}

// A 0.5 m cube spinning about the vertical on its face: four corner points,
// each carrying m g / 4, each a half-diagonal r = 0.25 sqrt 2 from the
// centre. Coulomb friction at each corner opposes its motion, which is
// tangential, so the torque is mu m g r and the spin falls at
// alpha = mu m g r / I, I = m s^2 / 6 = m / 24 (24 mu g r = 41.6 rad/s^2
// at mu 0.5), by alpha h a step, until it stops.
TEST(ManifoldFriction, SpinningCubeSlowsAtTheFourCornersCoulombRate) {
  const double mu = 0.5;
  const double h = 1.0 / 60.0;
  const double omega0 = 6.0;
  const double alpha = 24.0 * mu * kG * 0.25 * std::sqrt(2.0);
  World world = World::Create(Manifold(10)).Value();
  AddGround(world, mu);
  const BodyId box = AddCube(world, {0, 0.25, 0}, Vec3::Zero(), {0, omega0, 0}, mu);
  const int moving = static_cast<int>(std::floor(omega0 / (alpha * h)));
  for (int n = 1; n <= moving; ++n) {
    ASSERT_TRUE(world.Step(h));
    const BodyState s = world.GetBodyState(box).Value();
    // 1e-6 rad/s: the normal impulses the bound reads converge to m g h / 4
    // each; what the sweeps leave is far below that.
    EXPECT_NEAR(s.angularVelocity.y(), omega0 - alpha * h * n, 1e-6) << "step " << n;
    EXPECT_LT(s.linearVelocity.norm(), 1e-6) << "step " << n;  // a pure spin stays a spin
  }
  for (int n = 0; n < 5; ++n) ASSERT_TRUE(world.Step(h));
  EXPECT_LT(world.GetBodyState(box).Value().angularVelocity.norm(), 1e-6);
}

// Friction only removes energy: cubes launched with random slide and spin,
// on the ground and on a dynamic slab (so both bodies of a pair turn), lose
// kinetic plus potential energy every step (a wrong-signed or unbounded row
// would feed it) and end at rest. At 20 sweeps: the property is friction's,
// not convergence's. Measured, the largest one-step rise over these 12
// launches is 2.7e-3 J at 5 sweeps, 3.4e-6 J at 10 and exactly 0 at 15,
// 20, 40 and 80: a residual the sweeps remove (the warm start of a slip
// point that moves with a spinning cube's pressure), where a wrong-signed
// or unbounded row adds joules at any sweep count.
TEST(ManifoldFriction, NeverAddsEnergyAndBringsRandomLaunchesToRest) {
  Draw draw{777u};
  for (int trial = 0; trial < 12; ++trial) {
    const bool onSlab = trial % 2 == 1;
    const Vec3 velocity(draw(-2, 2), 0, draw(-2, 2));
    const Vec3 spin(0, draw(-8, 8), 0);
    const double mu = draw(0.2, 0.9);
    World world = World::Create(Manifold(20)).Value();
    AddGround(world, mu);
    std::vector<BodyId> bodies;
    double base = 0.0;
    if (onSlab) {
      bodies.push_back(world
                           .CreateBody({.type = BodyType::Dynamic,
                                        .position = {0, 0.1, 0},
                                        .shape = Box({3, 0.1, 3}),
                                        .density = 200.0,
                                        .friction = mu})
                           .Value());
      base = 0.2;
    }
    bodies.push_back(AddCube(world, {0, base + 0.25, 0}, velocity, spin, mu));
    const auto energy = [&world, &bodies] { return TotalEnergy(world, bodies); };
    double before = energy();
    for (int n = 0; n < 240; ++n) {
      ASSERT_TRUE(world.Step(1.0 / 60.0));
      const double now = energy();
      // 1e-6 J: round-off and the sweeps' residual on energies of 10-100 J;
      // a spin row of the wrong sign adds joules in one step.
      EXPECT_LE(now, before + 1e-6) << "trial " << trial << " step " << n;
      before = now;
    }
    const BodyState s = world.GetBodyState(bodies.back()).Value();
    EXPECT_LT(s.linearVelocity.norm() + s.angularVelocity.norm(), 1e-6) << "trial " << trial;
  }
}

// The per-point storage is exact for the manifold's impulses: sharing them
// out with slip shares and summing them back with the same shares gives
// the slip and the spin again (1e-12 of their scale: round-off), for random
// manifolds of 2-8 points and random loads on them (some points unloaded,
// or none: equal shares). The shared vectors lie in the contact plane and
// their moment about the points' mean is the slip's at the centre of
// pressure plus the spin.
TEST(ManifoldFriction, SharedImpulsesSumBackToTheManifoldsOwn) {
  Draw draw{4242u};
  for (int trial = 0; trial < 200; ++trial) {
    const int count = 2 + trial % 7;
    const auto size = static_cast<std::size_t>(count);
    const Vec3 n = Vec3(draw(-1, 1), draw(-1, 1), draw(-1, 1)).normalized();
    const Vec3 tangent[2] = {AnyPerpendicular(n), n.cross(AnyPerpendicular(n))};
    std::array<Vec3, kMaxManifoldPoints> points{};
    std::array<double, kMaxManifoldPoints> load{};
    for (std::size_t i = 0; i < size; ++i) {
      const Vec3 p(draw(-1, 1), draw(-1, 1), draw(-1, 1));
      points[i] = p - n * n.dot(p);  // a face: the points in one plane
      load[i] = trial % 5 == 0 ? 0.0 : std::max(draw(-0.5, 2.0), 0.0);
    }
    const auto position = [&points](int i) { return points[static_cast<std::size_t>(i)]; };
    std::array<Vec3, kMaxManifoldPoints> offsets{};
    const std::span<Vec3> offsetSpan(offsets.data(), size);
    const Vec3 mean = ManifoldOffsets(count, n, position, offsetSpan);
    std::array<double, kMaxManifoldPoints> shares{};
    const std::span<double> shareSpan(shares.data(), size);
    const Vec3 pressure =
        ManifoldSlipShares(count, std::span<const double>(load.data(), size), position, shareSpan);
    ManifoldFrictionImpulses impulses;
    impulses.slip[0] = draw(-10, 10);
    impulses.slip[1] = draw(-10, 10);
    impulses.spin = draw(-5, 5);
    std::array<Vec3, kMaxManifoldPoints> perPoint{};
    const std::span<Vec3> perPointSpan(perPoint.data(), size);
    ShareManifoldFriction(impulses, offsetSpan, shareSpan, n, tangent, perPointSpan);
    Vec3 moment = Vec3::Zero();
    for (std::size_t i = 0; i < size; ++i) {
      EXPECT_LT(std::abs(perPoint[i].dot(n)), 1e-12) << "trial " << trial;
      moment += (points[i] - mean).cross(perPoint[i]);
    }
    const Vec3 slip = impulses.slip[0] * tangent[0] + impulses.slip[1] * tangent[1];
    const Vec3 expectedMoment = (pressure - mean).cross(slip) + impulses.spin * n;
    EXPECT_LT((moment - expectedMoment).norm(), 1e-12 * 20) << "trial " << trial;
    const ManifoldFrictionImpulses back =
        SumManifoldFriction(perPointSpan, offsetSpan, shareSpan, n, tangent);
    EXPECT_NEAR(back.slip[0], impulses.slip[0], 1e-12 * 10) << "trial " << trial;
    EXPECT_NEAR(back.slip[1], impulses.slip[1], 1e-12 * 10) << "trial " << trial;
    EXPECT_NEAR(back.spin, impulses.spin, 1e-12 * 20) << "trial " << trial;
  }
}

// The impulses stored for the warm start are the ones that moved the body:
// by the impulse-momentum theorem their sum is m dv - m g h and their moment
// about the centre of mass I dw. A cube sliding and spinning on a plane,
// on both sides of its pair, several sweeps.
TEST(ManifoldFriction, StoredImpulsesAreTheOnesThatMovedTheBody) {
  for (const bool planeFirst : {true, false}) {
    WorldSettings settings = Manifold(10);
    settings.gravity = Vec3(0, -kG, 0);
    testing::ContactScene scene(settings);
    const double mass = 62.5;
    if (planeFirst) scene.AddPlane({.friction = 0.5});
    const int box = scene.AddBox({0, 0.25, 0}, Vec3::Constant(0.25), mass, Quat::Identity(), 0.5);
    if (!planeFirst) scene.AddPlane({.friction = 0.5});
    scene.Body(box).linearVelocity = Vec3(0.8, 0, -0.5);
    scene.Body(box).angularVelocity = Vec3(0, 2.0, 0);
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
    // 1e-9 of the weight's impulse m g h = 10 N s and of I w0 = 5 N m s:
    // round-off.
    const Vec3 expectedForce = mass * (after.linearVelocity - v0) - mass * h * settings.gravity;
    EXPECT_LT((force - expectedForce).norm(), 1e-9 * mass * kG * h) << "plane first " << planeFirst;
    const Vec3 expectedMoment = inertia * (after.angularVelocity - w0);
    EXPECT_LT((moment - expectedMoment).norm(), 1e-9 * (inertia * w0).norm()) << "plane first " << planeFirst;
    // And it did brake the spin and the slide (the scene tells it apart
    // from no friction).
    EXPECT_LT(after.angularVelocity.y(), w0.y() - 0.1) << "plane first " << planeFirst;
  }
}

// The coloured order's lanes hold per-point rows: refused there, naming the
// setting, instead of silently running the per-point rows.
TEST(ManifoldFriction, IsRefusedWithTheColouredOrder) {
  WorldSettings coloured = Manifold(10);
  coloured.methods.contactOrder = ContactOrder::ByColour;
  ExpectRefusedNaming(coloured, {"frictionSolve = PerManifold", "contactOrder = PairByPair"});
  // Without the normal block it has nothing to need: accepted.
  WorldSettings rowByRow = Manifold(10);
  rowByRow.methods.blockSolver = false;
  EXPECT_TRUE(World::Create(rowByRow));
}

// Sixteen cubes sliding and spinning into each other and to rest: the same
// bits at 1, 2 and 3 threads.
TEST(ManifoldFriction, BitIdenticalForAnyThreadCount) {
  ExpectSixteenCubesBitIdenticalForAnyThreadCount(Manifold(10));
}

}  // namespace manifold_friction_test
}  // namespace talus
