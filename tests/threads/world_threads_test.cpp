// WorldSettings::threads: the step gives the same bits for 1, 2, 3 and 8
// threads on scenes that exercise every parallel stage (many narrow-phase
// chunks of box and hull pairs, more than one integration chunk, sleeping
// and waking), and a bad thread count is refused with its name.
//
// The oracle is the single-threaded step: the parallel stages must not
// change a single bit of any body's state, of the contact points or of the
// step counts. No tolerance: the claim is bit-identity, so any difference is
// a bug (a race, or a result that depends on which thread ran which item).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "talus/hull_builder.h"
#include "talus/world.h"

namespace talus {
namespace world_threads_test {

constexpr double kH = 1.0 / 60.0;

Shape Box(const Vec3& half) { return Shape::CreateBox(half).Value(); }

void AddGround(World& world) {
  ASSERT_TRUE(
      world.CreateBody({.type = BodyType::Static, .position = {0, -0.5, 0}, .shape = Box({60, 0.5, 60})}));
}

// A pyramid of `height` layers of unit cubes: layer i is (height - i)^2
// cubes, offset by half a cube from the layer below.
void AddPyramid(World& world, int height) {
  for (int layer = 0; layer < height; ++layer) {
    const int side = height - layer;
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        const Vec3 position(j - 0.5 * (side - 1), layer + 0.5, k - 0.5 * (side - 1));
        ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                      .position = position,
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 1000.0}));
      }
    }
  }
}

// A side x side x side lattice of random convex hulls (12 random points
// each), slightly jittered and turned, dropped onto the ground.
void AddHullPile(World& world, int side, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < side * side * side; ++i) {
    std::vector<Vec3> points;
    for (int p = 0; p < 12; ++p)
      points.emplace_back(0.4 * unit(random), 0.4 * unit(random), 0.4 * unit(random));
    auto hull = BuildHull(points);
    ASSERT_TRUE(hull) << hull.GetError().message;
    const Vec3 position(1.1 * (i % side) + 0.05 * unit(random), 0.6 + 1.1 * (i / (side * side)),
                        1.1 * ((i / side) % side) + 0.05 * unit(random));
    const Quat orientation = Quat(1.0, unit(random), unit(random), unit(random)).normalized();
    ASSERT_TRUE(world.CreateBody(
        {.type = BodyType::Dynamic,
         .position = position,
         .orientation = orientation,
         .shape = Shape::CreateHull(std::make_shared<const Hull>(std::move(hull).Value())).Value(),
         .density = 500.0}));
  }
}

// `count` boxes of random sizes at random poses and velocities in a 12 m
// wide column: they fall, collide, pile up and (with sleeping on) fall
// asleep and are woken by later arrivals.
void AddRandomBoxes(World& world, int count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    const Vec3 half(0.2 + 0.4 * unit(random), 0.2 + 0.4 * unit(random), 0.2 + 0.4 * unit(random));
    const Vec3 position(12.0 * unit(random) - 6.0, 0.5 + 6.0 * unit(random), 12.0 * unit(random) - 6.0);
    const Quat orientation =
        Quat(1.0, unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5).normalized();
    ASSERT_TRUE(world.CreateBody(
        {.type = BodyType::Dynamic,
         .position = position,
         .orientation = orientation,
         .linearVelocity = {2.0 * unit(random) - 1.0, -2.0 * unit(random), 2.0 * unit(random) - 1.0},
         .angularVelocity = {unit(random), unit(random), unit(random)},
         .shape = Box(half),
         .density = 200.0 + 800.0 * unit(random)}));
  }
}

// Every double of every body's state, the contact points and the step's
// counts, as raw bits.
struct Fingerprint {
  std::vector<std::uint64_t> bits;
  std::int64_t manifolds = 0;
  std::int64_t spherePairs = 0;
  std::int64_t awakeBodies = 0;
  std::int64_t sleepingBodies = 0;
  int wakes = 0;                   ///< times a sleeping body woke up
  std::int64_t overflowPairs = 0;  ///< most pairs the coloured solver ran one by one in a step
  std::int64_t timedBounces = 0;   ///< points that bounced inside a step, over the run
  std::int64_t extraSweeps = 0;    ///< steps that ran more than the minimum velocity sweeps
};

void AppendBits(std::vector<std::uint64_t>& bits, const double* values, int n) {
  for (int i = 0; i < n; ++i) bits.push_back(std::bit_cast<std::uint64_t>(values[i]));
}

void AppendStats(std::vector<std::uint64_t>& bits, const StepStatistics& s) {
  for (const std::int64_t count : {s.bodies,
                                   s.awakeBodies,
                                   s.sleepingBodies,
                                   s.spherePairs,
                                   s.sleepingPairsSkipped,
                                   s.manifolds,
                                   s.manifoldsReused,
                                   s.reusedContactPoints,
                                   s.persistentPoints,
                                   s.contactPoints,
                                   s.frictionRows,
                                   s.frictionRowsSkipped,
                                   s.restitutionSkipped,
                                   s.timedBounces,
                                   s.warmStartedPoints,
                                   s.islands,
                                   s.velocitySweeps,
                                   s.solverColours,
                                   s.overflowPairs,
                                   s.narrowPhase.pairsTested,
                                   s.narrowPhase.satTests,
                                   s.narrowPhase.satCacheHits,
                                   s.narrowPhase.edgeAxesTested,
                                   s.narrowPhase.manifoldPoints}) {
    bits.push_back(static_cast<std::uint64_t>(count));
  }
}

using SceneBuilder = void (*)(World&);

// Builds the scene with `settings` at `threads` threads, steps it `steps`
// times and fingerprints every step.
Fingerprint Simulate(SceneBuilder build, WorldSettings settings, int threads, int steps) {
  settings.threads = threads;
  auto created = World::Create(settings);
  EXPECT_TRUE(created) << created.GetError().message;
  World world = std::move(created).Value();
  build(world);
  Fingerprint print;
  std::vector<bool> awake;
  for (int n = 0; n < steps; ++n) {
    const auto stats = world.Step(kH);
    EXPECT_TRUE(stats) << stats.GetError().message;
    if (!stats) return print;
    AppendStats(print.bits, stats.Value());
    print.manifolds = std::max(print.manifolds, stats.Value().manifolds);
    print.spherePairs = std::max(print.spherePairs, stats.Value().spherePairs);
    print.awakeBodies = std::max(print.awakeBodies, stats.Value().awakeBodies);
    print.sleepingBodies = std::max(print.sleepingBodies, stats.Value().sleepingBodies);
    print.overflowPairs = std::max(print.overflowPairs, stats.Value().overflowPairs);
    print.timedBounces += stats.Value().timedBounces;
    if (stats.Value().velocitySweeps > settings.velocityIterations) ++print.extraSweeps;
    for (const BodyId id : world.BodyIds()) {
      const BodyState state = world.GetBodyState(id).Value();
      AppendBits(print.bits, state.position.data(), 3);
      AppendBits(print.bits, state.orientation.coeffs().data(), 4);
      AppendBits(print.bits, state.linearVelocity.data(), 3);
      AppendBits(print.bits, state.angularVelocity.data(), 3);
      print.bits.push_back(state.awake ? 1u : 0u);
      const auto slot = static_cast<std::size_t>(id.index);
      if (awake.size() <= slot) awake.resize(slot + 1, true);
      if (state.awake && !awake[slot]) ++print.wakes;
      awake[slot] = state.awake;
    }
    for (const ContactPointInfo& point : world.GetContactPoints()) {
      AppendBits(print.bits, point.position.data(), 3);
      AppendBits(print.bits, point.normal.data(), 3);
      AppendBits(print.bits, &point.depth, 1);
    }
  }
  return print;
}

// The scene at 2, 3 and 8 threads against 1 thread, bit for bit; returns
// the 1-thread fingerprint.
Fingerprint ExpectSameBitsForEveryThreadCount(SceneBuilder build, const WorldSettings& settings, int steps) {
  const Fingerprint reference = Simulate(build, settings, 1, steps);
  for (const int threads : {2, 3, 8}) {
    const Fingerprint threaded = Simulate(build, settings, threads, steps);
    EXPECT_EQ(threaded.bits.size(), reference.bits.size()) << threads << " threads";
    if (threaded.bits.size() != reference.bits.size()) continue;
    std::size_t firstDifference = reference.bits.size();
    for (std::size_t i = 0; i < reference.bits.size(); ++i) {
      if (threaded.bits[i] != reference.bits[i]) {
        firstDifference = i;
        break;
      }
    }
    EXPECT_EQ(firstDifference, reference.bits.size())
        << threads << " threads differ from 1 at word " << firstDifference;
  }
  return reference;
}

TEST(WorldThreads, PyramidIsBitIdenticalForAnyThreadCount) {
  const auto build = [](World& world) {
    AddGround(world);
    AddPyramid(world, 7);  // 140 cubes: two integration chunks, ~60 narrow-phase chunks
  };
  const Fingerprint one = ExpectSameBitsForEveryThreadCount(build, WorldSettings{}, 20);
  // The scene reaches the parallel paths: several chunks of each kind.
  EXPECT_GT(one.awakeBodies, 128);
  EXPECT_GT(one.manifolds, 4 * 8);
}

TEST(WorldThreads, HullPileIsBitIdenticalForAnyThreadCount) {
  const auto build = [](World& world) {
    AddGround(world);
    AddHullPile(world, 4, 7);  // 64 hulls falling into each other and the ground
  };
  const Fingerprint one = ExpectSameBitsForEveryThreadCount(build, WorldSettings{}, 60);
  EXPECT_GT(one.manifolds, 2 * 8);
}

TEST(WorldThreads, RandomBoxesWithSleepingAreBitIdenticalForAnyThreadCount) {
  const auto build = [](World& world) {
    AddGround(world);
    AddRandomBoxes(world, 160, 11);
  };
  WorldSettings settings;
  settings.timeToSleep = 0.2;  // islands fall asleep within the run and are woken by later arrivals
  const Fingerprint one = ExpectSameBitsForEveryThreadCount(build, settings, 100);
  EXPECT_GT(one.manifolds, 8 * 8);
  EXPECT_GT(one.awakeBodies, 128);
  EXPECT_GT(one.sleepingBodies, 0);
  EXPECT_GT(one.wakes, 0);
}

TEST(WorldThreads, EverySolverVariantIsBitIdentical) {
  const auto build = [](World& world) {
    AddGround(world);
    AddRandomBoxes(world, 60, 5);
  };
  WorldSettings split;
  split.methods.positionCorrection = PositionCorrection::SplitImpulses;
  split.methods.rotation = RotationIntegrator::MomentumSplitting;
  ExpectSameBitsForEveryThreadCount(build, split, 40);
  WorldSettings writeUp;
  writeUp.methods.narrowPhase.satMode = SatMode::Full;
  writeUp.methods.narrowPhase.manifoldMode = ManifoldMode::WriteUp;
  writeUp.methods.narrowPhase.reuseDistance = 0.0;
  writeUp.methods.blockSolver = false;  // the write-up's row-by-row solver, friction per point
  writeUp.methods.frictionSolve = FrictionSolve::PerPoint;
  writeUp.methods.speculativeMotion = false;  // and its fixed speculative margin
  writeUp.methods.translation = TranslationIntegrator::ExactConstantAcceleration;
  writeUp.broadPhase = BroadPhaseKind::AabbTree;
  ExpectSameBitsForEveryThreadCount(build, writeUp, 40);
}

// The coloured wide solver spreads each colour's bundles over the pool
// (world_step.cpp's range runner): a pyramid has enough pairs per colour for
// several chunks of bundles, and the result must not depend on who solved
// which chunk.
TEST(WorldThreads, ColouredSolverSpreadsColoursWithoutChangingABit) {
  const auto build = [](World& world) {
    AddGround(world);
    AddPyramid(world, 7);
  };
  WorldSettings coloured;
  coloured.methods.contactOrder = ContactOrder::ByColour;
  coloured.methods.frictionSolve = FrictionSolve::PerPoint;  // the coloured solver has no coupled block
  const Fingerprint one = ExpectSameBitsForEveryThreadCount(build, coloured, 12);
  EXPECT_GT(one.manifolds, 2 * 8 * 8);  // several chunks of 8 bundles of 4 pairs
}

// Every part of the coloured solver that runs on the pool, in one scene:
// Prepare's pairs (48 bouncing boxes: restitution and timed bounces, counted
// per chunk), the packing, the warm start, the untracked sweeps as one
// chain and the tracked extra sweeps one chain each, the overflow pairs
// between the colours (the boxes land on one dynamic slab: its pairs past
// the 24 colours go to the overflow colour), the unpacking, split impulses
// after it, and the parallel gather of the contacts.
void AddBouncingBoxesOnASlab(World& world) {
  ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {0.0, 0.2, 0.0},
                                .shape = Box({3.6, 0.2, 3.6}),
                                .density = 1000.0}));
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // 36 boxes 1 mm above the slab, one per cell of a 6 x 6 grid (36 pairs
  // with the slab from the first steps: 12 past the 24 colours), and 12
  // dropped onto them, bouncing.
  for (int i = 0; i < 48; ++i) {
    const Vec3 half(0.2 + 0.25 * unit(random), 0.2 + 0.25 * unit(random), 0.2 + 0.25 * unit(random));
    const bool resting = i < 36;
    const Vec3 position(1.1 * (i % 6) - 2.75, resting ? 0.401 + half.y() : 1.6 + 0.5 * unit(random),
                        1.1 * ((i / 6) % 6) - 2.75);
    const Quat orientation =
        resting ? Quat::Identity()
                : Quat(1.0, unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5).normalized();
    ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                  .position = position,
                                  .orientation = orientation,
                                  .linearVelocity = {0.0, resting ? 0.0 : -3.0 * unit(random), 0.0},
                                  .shape = Box(half),
                                  .density = 300.0 + 700.0 * unit(random),
                                  .restitution = 0.6 * unit(random)}));
  }
}

TEST(WorldThreads, ColouredSolverWithOverflowBouncesAndSplitImpulsesIsBitIdentical) {
  const auto build = [](World& world) {
    AddGround(world);
    AddBouncingBoxesOnASlab(world);
  };
  WorldSettings settings;
  settings.methods.contactOrder = ContactOrder::ByColour;
  settings.methods.frictionSolve = FrictionSolve::PerPoint;  // the coloured solver has no coupled block
  settings.methods.positionCorrection = PositionCorrection::SplitImpulses;
  const Fingerprint one = ExpectSameBitsForEveryThreadCount(build, settings, 30);
  // The scene reaches what it is here for.
  EXPECT_GT(one.overflowPairs, 0);
  EXPECT_GT(one.timedBounces, 0);
  EXPECT_GT(one.extraSweeps, 0);
  EXPECT_GT(one.manifolds, 32);  // more than one chunk of Prepare's 32 pairs and of 8 bundles
}

// Changing the thread count between steps changes nothing either.
TEST(WorldThreads, ChangingTheThreadCountMidRunChangesNoBit) {
  const auto build = [](World& world) {
    AddGround(world);
    AddRandomBoxes(world, 60, 3);
  };
  const auto run = [&](bool switchThreads) {
    World world;
    build(world);
    std::vector<std::uint64_t> bits;
    for (int n = 0; n < 40; ++n) {
      if (switchThreads && n % 10 == 5) {
        WorldSettings settings = world.Settings();
        settings.threads = 1 + (n / 10) % 3 * 2;  // 1, 3, 5, 1
        EXPECT_TRUE(world.SetSettings(settings));
      }
      EXPECT_TRUE(world.Step(kH));
    }
    for (const BodyId id : world.BodyIds()) {
      const BodyState state = world.GetBodyState(id).Value();
      AppendBits(bits, state.position.data(), 3);
      AppendBits(bits, state.orientation.coeffs().data(), 4);
      AppendBits(bits, state.linearVelocity.data(), 3);
      AppendBits(bits, state.angularVelocity.data(), 3);
    }
    return bits;
  };
  EXPECT_EQ(run(true), run(false));
}

TEST(WorldThreads, BadThreadCountsAreRefusedByName) {
  for (const int threads : {0, -1, kMaxThreads + 1}) {
    WorldSettings settings;
    settings.threads = threads;
    const auto created = World::Create(settings);
    ASSERT_FALSE(created);
    EXPECT_EQ(created.GetError().message, "WorldSettings.threads = " + std::to_string(threads) +
                                              " is outside [1, " + std::to_string(kMaxThreads) + "]");
    // A refused change leaves the world's settings as they were.
    World world;
    EXPECT_FALSE(world.SetSettings(settings));
    EXPECT_EQ(world.Settings().threads, 1);
  }
  WorldSettings most;
  most.threads = 4;
  EXPECT_TRUE(World::Create(most));
  EXPECT_EQ(WorldSettings{}.threads, 1);
}

}  // namespace world_threads_test
}  // namespace talus
