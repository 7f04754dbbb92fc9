// The persistent contact store (world/world_collide.h): contacts are updated
// in place while the pair list keeps its order, and rebuilt in the spare
// buffers when a pair joins or leaves the list before others. Either way
// every persisting contact must start the step from its own impulses.
//
// The oracle is the physics of a warm start with one sweep: a box resting
// on the floor under row-by-row rows and a single velocity sweep stays at
// rest only if its rows start from its own impulses (its weight per step,
// m g h). Two resting boxes of 1 and 8 kg sit on either side of the slot
// where a third box's pair joins the list (it lands) or leaves it (it is
// lifted away). Measured on the 8 kg box: one step started from zero
// impulses (warm starting switched off for that step) leaves it moving at
// 5.8e-3 m/s and turning at 0.021 rad/s, where a warm-started rest stays
// below 5e-11 m/s and 6e-9 rad/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "talus/world.h"

namespace talus {
namespace contact_store_test {

constexpr double kH = 1.0 / 60.0;

Shape Box(double half) { return Shape::CreateBox(Vec3::Constant(half)).Value(); }

// One sweep, row by row, no extra sweeps for persisting pairs: what the
// contacts start from is what they end with, give or take one sweep.
WorldSettings OneSweepSettings(bool warmStarting) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.velocityIterations = 1;
  settings.methods.maxVelocityIterations = 1;
  settings.methods.blockSolver = false;
  settings.methods.frictionSolve = FrictionSolve::PerPoint;
  settings.methods.warmStarting = warmStarting;
  return settings;
}

// Floor (body 0), a light box (body 1, 1 kg), a box that can land between
// them in the pair list (body 2), a heavy box (body 3, 8 kg): the floor's
// pairs are ordered (0, 1), (0, 2), (0, 3), 3 m apart so that only the
// floor joins them.
struct Scene {
  World world;
  BodyId light;
  BodyId middle;
  BodyId heavy;
};

Scene MakeScene(const WorldSettings& settings, double middleHeight) {
  World world = World::Create(settings).Value();
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static,
                                .position = {0, -0.5, 0},
                                .shape = Shape::CreateBox({50, 0.5, 50}).Value()}));
  const auto box = [&world](const Vec3& position, double density) {
    return world
        .CreateBody({.type = BodyType::Dynamic, .position = position, .shape = Box(0.5), .density = density})
        .Value();
  };
  const BodyId light = box({-3, 0.5, 0}, 1000.0);
  const BodyId middle = box({0, middleHeight, 3}, 1000.0);
  const BodyId heavy = box({3, 0.5, 0}, 8000.0);
  return {std::move(world), light, middle, heavy};
}

double VerticalSpeed(const World& world, BodyId id) {
  return std::abs(world.GetBodyState(id).Value().linearVelocity.y());
}

double TurnRate(const World& world, BodyId id) {
  return world.GetBodyState(id).Value().angularVelocity.norm();
}

StepStatistics MustStep(World& world) {
  const Result<StepStatistics> stats = world.Step(kH);
  EXPECT_TRUE(stats);
  return stats ? stats.Value() : StepStatistics{};
}

// Between the two (the header's figures) by more than three orders either
// way: m/s for the speed, rad/s for the turn rate.
constexpr double kRestSpeed = 1e-6;
constexpr double kRestTurnRate = 1e-6;

// Steps `scene` to step `end`, checking from step 60 (the resting boxes
// have settled) that both resting boxes stay at rest; returns the steps
// whose manifold count differed from the step before (a pair joined or
// left the list).
int StepCheckingRest(Scene& scene, int begin, int end, std::int64_t& lastManifolds) {
  int changes = 0;
  for (int n = begin; n < end; ++n) {
    const StepStatistics stats = MustStep(scene.world);
    if (n > 0 && stats.manifolds != lastManifolds) ++changes;
    lastManifolds = stats.manifolds;
    if (n < 60) continue;
    EXPECT_LT(VerticalSpeed(scene.world, scene.light), kRestSpeed) << "step " << n;
    EXPECT_LT(VerticalSpeed(scene.world, scene.heavy), kRestSpeed) << "step " << n;
    EXPECT_LT(TurnRate(scene.world, scene.light), kRestTurnRate) << "step " << n;
    EXPECT_LT(TurnRate(scene.world, scene.heavy), kRestTurnRate) << "step " << n;
  }
  return changes;
}

TEST(ContactStore, RestingBoxesKeepTheirOwnImpulsesWhenAPairJoinsTheListBetweenThem) {
  // The middle box falls 19.5 m and lands near step 120, after the others
  // have settled.
  Scene scene = MakeScene(OneSweepSettings(true), 20.0);
  std::int64_t manifolds = 0;
  EXPECT_EQ(StepCheckingRest(scene, 0, 240, manifolds), 1);
  EXPECT_EQ(manifolds, 3);
}

TEST(ContactStore, RestingBoxesKeepTheirOwnImpulsesWhenAPairLeavesTheListBetweenThem) {
  // The middle box rests with the others, then is lifted 10 m: its pair
  // leaves the list and the heavy box's contact moves down a slot.
  Scene scene = MakeScene(OneSweepSettings(true), 0.5);
  std::int64_t manifolds = 0;
  EXPECT_EQ(StepCheckingRest(scene, 0, 90, manifolds), 0);
  EXPECT_EQ(manifolds, 3);
  ASSERT_TRUE(scene.world.SetTransform(scene.middle, {0, 10.5, 3}, Quat::Identity()));
  EXPECT_EQ(StepCheckingRest(scene, 90, 150, manifolds), 1);
  EXPECT_EQ(manifolds, 2);
}

TEST(ContactStore, EveryPersistingPointIsWarmStartedInPlaceAndAfterTheListMoves) {
  // In a step with last step's pairs and points, every point finds its
  // impulses (the list in place); in the step a pair joins (the list
  // moves), the resting boxes' eight points do and the new pair's none.
  // While the middle box settles its manifold gains points (1 to 4), which
  // start from zero: those steps are left out.
  Scene scene = MakeScene(OneSweepSettings(true), 20.0);
  StepStatistics last = MustStep(scene.world);
  int joins = 0;
  int inPlace = 0;
  for (int n = 1; n < 240; ++n) {
    const StepStatistics stats = MustStep(scene.world);
    if (stats.manifolds != last.manifolds) {
      ++joins;
      EXPECT_EQ(stats.warmStartedPoints, 8) << "step " << n;
    } else if (stats.contactPoints == last.contactPoints) {
      ++inPlace;
      EXPECT_EQ(stats.warmStartedPoints, stats.contactPoints) << "step " << n;
    }
    last = stats;
  }
  EXPECT_EQ(joins, 1);
  EXPECT_GT(inPlace, 200);
}

TEST(ContactStore, WithoutWarmStartingNoPointCountsAsWarmStarted) {
  Scene scene = MakeScene(OneSweepSettings(false), 20.0);
  for (int n = 0; n < 240; ++n) EXPECT_EQ(MustStep(scene.world).warmStartedPoints, 0) << "step " << n;
}

}  // namespace contact_store_test
}  // namespace talus
