// FrictionSolve::Adaptive, the default: the manifold's rows on every pair,
// the coupled block on a pair that carries more than 50 weights of its
// lighter body. First the rule on hand-built contacts (its threshold,
// worked out by hand), then which rows real scenes get
// (StepStatistics::frictionRows tells them apart: three rows for a pair on
// manifold rows, two per point otherwise), then the physics the choice must
// keep (the discrete Coulomb stop, a box held on a slope, a 1000:1 load that
// manifold rows alone throw), then refusals and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "dynamics/adaptive_friction.h"
#include "friction_scenes.h"
#include "talus/world.h"

namespace talus {
namespace adaptive_friction_test {

using namespace friction_scenes;  // NOLINT(google-build-using-namespace): the shared scenes

WorldSettings Adaptive(int iterations) { return Settings(FrictionSolve::Adaptive, iterations); }

// A solid cube's inertia, m s^2 / 6 about every axis.
Mat3 CubeInertia(double mass, double side) { return Mat3::Identity() * mass * side * side / 6.0; }

// A four-point face contact with mu 0.5 whose points carry `normal` each
// and the friction vector `friction` each (stored impulses, N s).
Contact FaceContact(double normal, const Vec3& friction) {
  Contact contact;
  contact.friction = 0.5;
  contact.manifold.pointCount = 4;
  contact.manifold.normal = Vec3::UnitY();
  for (int i = 0; i < 4; ++i) {
    contact.normalImpulse[static_cast<std::size_t>(i)] = normal;
    contact.frictionImpulse[static_cast<std::size_t>(i)] = friction;
  }
  return contact;
}

// The rule by hand: a 1 kg body at 60 Hz weighs m g h = 0.1635 N s a step;
// 50 of those is 8.175 N s, 2.04 N s a point of four.
TEST(AdaptiveFriction, RuleCountsTheLoadInWeightsOfTheLighterMovingBody) {
  const double h = 1.0 / 60.0;
  const double weight = 1.0 * kG * h;
  // Its own weight on static ground: manifold rows.
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(weight / 4, Vec3::Zero()), 1.0, 0.0, kG, h));
  // 49 and 51 weights, the lighter body on either side of the pair.
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(49 * weight / 4, Vec3::Zero()), 1.0, 0.0, kG, h));
  EXPECT_TRUE(AdaptiveNeedsCoupledBlock(FaceContact(51 * weight / 4, Vec3::Zero()), 1.0, 0.0, kG, h));
  EXPECT_TRUE(AdaptiveNeedsCoupledBlock(FaceContact(51 * weight / 4, Vec3::Zero()), 1e-3, 1.0, kG, h));
  // The same load through a 10 kg body is 5.1 of its weights.
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(51 * weight / 4, Vec3::Zero()), 0.1, 0.0, kG, h));
  // Friction does not enter: a sliding pair at its cone under a light load
  // keeps the manifold rows.
  EXPECT_FALSE(
      AdaptiveNeedsCoupledBlock(FaceContact(weight / 4, Vec3(0.5 * weight / 4, 0, 0)), 1.0, 0.0, kG, h));
  // No gravity, no weight to count in: manifold rows.
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(1e6, Vec3::Zero()), 1.0, 0.0, 0.0, h));
  // A new pair has nothing stored: on the ground, manifold rows; between
  // two moving bodies the heavier may rest its weight on the lighter, so
  // their mass ratio counts: 49:1 no, 51:1 yes.
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(0.0, Vec3::Zero()), 1.0, 0.0, kG, h));
  EXPECT_FALSE(AdaptiveNeedsCoupledBlock(FaceContact(0.0, Vec3::Zero()), 1.0, 1.0 / 49, kG, h));
  EXPECT_TRUE(AdaptiveNeedsCoupledBlock(FaceContact(0.0, Vec3::Zero()), 1.0 / 51, 1.0, kG, h));
  // One or two points count the same way.
  Contact edge = FaceContact(51 * weight / 2, Vec3::Zero());
  edge.manifold.pointCount = 2;
  EXPECT_TRUE(AdaptiveNeedsCoupledBlock(edge, 1.0, 0.0, kG, h));
}

TEST(AdaptiveFriction, IsTheDefault) {
  EXPECT_EQ(WorldSettings{}.methods.frictionSolve, FrictionSolve::Adaptive);
}

// A 0.5 m, 1 kg cube resting on the ground at x.
void AddLightCube(World& world, double x) {
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {x, 0.25, 0},
                                .shape = Box(Vec3::Constant(0.25)),
                                .mass = 1.0,
                                .localInertia = CubeInertia(1.0, 0.5),
                                .friction = 0.6}));
}

// The friction rows of the last of `steps` steps of a 0.5 m, 1 kg cube on
// static ground under a 1 m slab of `load` kg (two pairs).
std::int64_t RowsUnderASlab(double load, int steps) {
  World world = World::Create(Adaptive(10)).Value();
  AddGround(world, 0.6);
  AddLightCube(world, 0.0);
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {0, 0.6, 0},
                                .shape = Box({0.5, 0.1, 0.5}),
                                .mass = load,
                                .localInertia = CubeInertia(load, 1.0),
                                .friction = 0.6}));
  std::int64_t rows = 0;
  for (int n = 0; n < steps; ++n) rows = world.Step(1.0 / 60.0).Value().frictionRows;
  return rows;
}

// Under a 10 kg slab the cube's pairs carry 11 and 10 of its weights: the
// manifold's three rows each. Under 100 kg, 101 and 100 weights (and a
// 100:1 pair from the first step, before anything is stored): the coupled
// block's per-point rows, two for each of the four points of each face.
TEST(AdaptiveFriction, ALightBodyUnderAHeavyLoadTakesTheCoupledBlockAndOnlyThen) {
  EXPECT_EQ(RowsUnderASlab(10.0, 1), 6);
  EXPECT_EQ(RowsUnderASlab(10.0, 30), 6);
  EXPECT_EQ(RowsUnderASlab(100.0, 1), 16);
  EXPECT_EQ(RowsUnderASlab(100.0, 30), 16);
}

// The coupled block goes to the whole group a loaded pair belongs to: a
// 1 kg cube beside the loaded one, touching it, takes it too; one standing
// apart keeps the manifold rows. Rows: 16 for the loaded pair and its
// ground pair, 8 for the neighbour's ground pair, 8 for the side contact
// of the two cubes (its four points) in the first case; 3 for the lone
// cube's ground pair in the second.
TEST(AdaptiveFriction, TheCoupledBlockGoesToTheLoadedPairsWholeGroup) {
  for (const bool touching : {true, false}) {
    World world = World::Create(Adaptive(10)).Value();
    AddGround(world, 0.6);
    for (const double x : {0.0, touching ? 0.5 : 2.0}) AddLightCube(world, x);
    EXPECT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                  .position = {0, 0.6, 0},
                                  .shape = Box({0.2, 0.1, 0.2}),
                                  .mass = 100.0,
                                  .localInertia = CubeInertia(100.0, 0.5),
                                  .friction = 0.6}));
    std::int64_t rows = 0;
    for (int n = 0; n < 30; ++n) rows = world.Step(1.0 / 60.0).Value().frictionRows;
    EXPECT_EQ(rows, touching ? 16 + 8 + 8 : 16 + 3) << "touching " << touching;
  }
}

// A sliding box under its own weight is on the manifold rows: their stop
// converges with the sweeps (the bounds as in manifold_friction_test.cpp:
// a Coulomb bound off by 1% moves the 0.5 m stop by 5 mm, and a residual
// that does not shrink with the sweeps fails the second).
TEST(AdaptiveFriction, SlidingBoxStopsAtTheDiscreteCoulombDistance) {
  for (const auto& [sweeps, bound] : {std::pair{10, 1e-4}, std::pair{20, 1e-6}}) {
    for (const double mu : {0.3, 0.8}) {
      for (const double h : {1.0 / 30.0, 1.0 / 60.0}) {
        const Stop stop = SlideAndStop(Adaptive(sweeps), 3.0, mu, h);
        EXPECT_NEAR(stop.distance, DiscreteStopDistance(3.0, mu, h), bound)
            << "sweeps " << sweeps << " mu " << mu << " h " << h;
        EXPECT_LT(stop.restSpeed, 1e-6) << "sweeps " << sweeps << " mu " << mu << " h " << h;
      }
    }
  }
}

TEST(AdaptiveFriction, BoxOnASlopeBelowTheFrictionAngleStaysPut) {
  // tan(20 deg) = 0.36 < mu = 0.5: static friction holds. 1e-6 m in 2 s.
  const double angle = 20.0 * std::numbers::pi / 180.0;
  EXPECT_LT(std::abs(SlopeDisplacement(Adaptive(10), angle, 0.5, 1.0 / 60.0, 120)), 1e-6);
}

// The largest distance any box of a 3-2-1 pyramid of 1 kg, 0.5 m cubes
// ends from where it was placed, and the largest rise of total energy over
// a step, after 5 s at 60 Hz under a 1 m cube of `load` kg.
struct LoadedPyramid {
  double moved = 0.0;       ///< m
  double energyRise = 0.0;  ///< J
};
LoadedPyramid PyramidUnderALoad(const WorldSettings& settings, double load) {
  World world = World::Create(settings).Value();
  AddGround(world, 0.6);
  std::vector<BodyId> boxes;
  std::vector<Vec3> placed;
  for (int row = 0; row < 3; ++row) {
    for (int i = 0; i < 3 - row; ++i) {
      const Vec3 at(-0.5 + 0.25 * row + 0.5 * i, 0.25 + 0.5 * row, 0);
      boxes.push_back(world
                          .CreateBody({.type = BodyType::Dynamic,
                                       .position = at,
                                       .shape = Box(Vec3::Constant(0.25)),
                                       .mass = 1.0,
                                       .localInertia = CubeInertia(1.0, 0.5),
                                       .friction = 0.6})
                          .Value());
      placed.push_back(at);
    }
  }
  const BodyId heavy = world
                           .CreateBody({.type = BodyType::Dynamic,
                                        .position = {0, 2.0, 0},
                                        .shape = Box(Vec3::Constant(0.5)),
                                        .mass = load,
                                        .localInertia = CubeInertia(load, 1.0),
                                        .friction = 0.6})
                           .Value();
  std::vector<BodyId> all = boxes;
  all.push_back(heavy);
  const auto energy = [&world, &all] { return TotalEnergy(world, all); };
  LoadedPyramid result;
  double before = energy();
  for (int n = 0; n < 300; ++n) {
    EXPECT_TRUE(world.Step(1.0 / 60.0));
    const double now = energy();
    result.energyRise = std::max(result.energyRise, now - before);
    before = now;
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    result.moved = std::max(result.moved, (world.GetBodyState(boxes[i]).Value().position - placed[i]).norm());
  }
  return result;
}

// A 1000 kg box on a pyramid of 1 kg boxes (the testbed's
// heavy_box_on_pyramid): every box stays within one slop (4 mm) per contact
// layer below it, three layers, 12 mm, and the energy never rises by more
// than the sweeps' residual (1 J against the load's 1.5e4 J of potential
// energy above the ground; a thrown load gains thousands). Manifold rows on
// every face throw it: the load test is what holds it.
TEST(AdaptiveFriction, APyramidOfLightBoxesHoldsAThousandTimesItsWeight) {
  const LoadedPyramid adaptive = PyramidUnderALoad(Adaptive(10), 1000.0);
  EXPECT_LT(adaptive.moved, 0.012);
  EXPECT_LT(adaptive.energyRise, 1.0);
  const LoadedPyramid manifold = PyramidUnderALoad(Settings(FrictionSolve::PerManifold, 10), 1000.0);
  EXPECT_GT(manifold.moved, 0.012) << "the scene no longer needs the load test; find one that does";
}

// Both halves of the rule need what CoupledBlock needs.
TEST(AdaptiveFriction, IsRefusedWithTheColouredOrderAndWithoutTheBlockSolver) {
  WorldSettings coloured = Adaptive(10);
  coloured.methods.contactOrder = ContactOrder::ByColour;
  ExpectRefusedNaming(coloured, {"frictionSolve = Adaptive", "contactOrder = PairByPair"});
  WorldSettings rowByRow = Adaptive(10);
  rowByRow.methods.blockSolver = false;
  ExpectRefusedNaming(rowByRow, {"frictionSolve = Adaptive", "blockSolver = true"});
}

// Sixteen cubes sliding and spinning into each other and to rest (pairs
// change rows as they slow): the same bits at 1, 2 and 3 threads.
TEST(AdaptiveFriction, BitIdenticalForAnyThreadCount) {
  ExpectSixteenCubesBitIdenticalForAnyThreadCount(Adaptive(10));
}

}  // namespace adaptive_friction_test
}  // namespace talus
