// Manifold reuse through the whole step (NarrowPhaseSettings::reuseDistance):
// a resting box reuses its manifold and rests where it rests without reuse,
// a sliding box still stops at the Coulomb distance, a turning body gets a
// fresh manifold once it has turned past the threshold counted from the
// pose the narrow phase last saw (not from last step's), reuse off runs the
// narrow phase for every pair, and the option is validated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "talus/contact_query.h"
#include "talus/world.h"

namespace talus {
namespace manifold_reuse_world_test {

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

// The shipped reuse distance (0.5 mm).
const double kDefaultReuse = NarrowPhaseSettings{}.reuseDistance;

Shape Box(const Vec3& half) { return Shape::CreateBox(half).Value(); }

WorldSettings Settings(double reuseDistance) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.methods.narrowPhase.reuseDistance = reuseDistance;
  return settings;
}

// A 100 m floor (the lower slot, so body A of its pairs) and a 1 m box of
// `friction` resting on it.
struct FloorAndBox {
  World world;
  BodyId box;
};

FloorAndBox MakeFloorAndBox(const WorldSettings& settings, double friction = 0.5) {
  World world = World::Create(settings).Value();
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static,
                                .position = {0, -0.5, 0},
                                .shape = Box({50, 0.5, 50}),
                                .friction = friction}));
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = {0, 0.5, 0},
                                      .shape = Box(Vec3::Constant(0.5)),
                                      .density = 1000.0,
                                      .friction = friction})
                         .Value();
  return {std::move(world), box};
}

StepStatistics MustStep(World& world) {
  const Result<StepStatistics> stats = world.Step(kH);
  EXPECT_TRUE(stats);
  return stats ? stats.Value() : StepStatistics{};
}

// Rest height of the box after 10 s, and the steps of the last 9 s that
// reused the manifold.
struct RestRun {
  double height = 0.0;
  int reusedSteps = 0;
};

RestRun RunResting(double reuseDistance) {
  FloorAndBox scene = MakeFloorAndBox(Settings(reuseDistance));
  RestRun run;
  for (int n = 0; n < 600; ++n) {
    const StepStatistics stats = MustStep(scene.world);
    EXPECT_EQ(stats.manifolds, 1);
    if (n >= 60 && stats.manifoldsReused == 1) ++run.reusedSteps;
  }
  run.height = scene.world.GetBodyState(scene.box).Value().position.y();
  return run;
}

TEST(ManifoldReuse, RestingBoxReusesItsManifoldAndRestsWhereItRestsWithout) {
  const RestRun with = RunResting(kDefaultReuse);
  const RestRun without = RunResting(0.0);
  // After the first second the box has settled to well under a micrometre
  // of motion, so every step reuses the manifold computed when it settled.
  EXPECT_EQ(with.reusedSteps, 540);
  EXPECT_EQ(without.reusedSteps, 0);
  // The rebuilt depths of a resting box on a floor are exact (incident
  // vertices under a reference face of A, collision/manifold_reuse.h), so
  // the rest height is the same to round-off; 1e-6 m is the brief's bar.
  EXPECT_NEAR(with.height, without.height, 1e-6);
  EXPECT_NEAR(with.height, 0.5, 0.005);  // within the Baumgarte slop
}

// The box_slide case (v0 = 5 m/s, mu = 0.5) with reuse on: it slides 4 cm
// a step at first (no reuse) and reuses once slower than reuseDistance / h
// (default distance).
TEST(ManifoldReuse, SlidingBoxStopsAtTheCoulombDistanceWithReuse) {
  FloorAndBox scene = MakeFloorAndBox(Settings(kDefaultReuse), 0.5);
  ASSERT_TRUE(scene.world.SetLinearVelocity(scene.box, {5, 0, 0}));
  const double h = 1.0 / 120.0;
  int reused = 0;
  for (int n = 0; n < 1000 && scene.world.GetBodyState(scene.box).Value().linearVelocity.x() > 1e-4; ++n) {
    const Result<StepStatistics> stats = scene.world.Step(h);
    ASSERT_TRUE(stats);
    reused += stats.Value().manifoldsReused;
  }
  EXPECT_GT(reused, 0);
  const double expected = 25.0 / (2.0 * 0.5 * kG);
  // The same 2% as WorldPhysics.SlidingBoxStopsAtTheCoulombDistance (the
  // discrete scheme stops v0 h / 2 = 2 cm short, 0.8%).
  EXPECT_NEAR(scene.world.GetBodyState(scene.box).Value().position.x(), expected, 0.02 * expected);
}

// A frictionless box spinning about the vertical at omega moves its corners
// (sqrt(3)/2 m from its centre) by omega h sqrt(3)/2 a step relative to the
// floor. At 0.3 mm a step under a 1 mm reuse distance, the motion counted
// from the pose of the last fresh manifold reaches 0.3, 0.6, 0.9, then 1.2
// mm: three reused steps, then a fresh one, again and again. Counting from
// last step's pose instead would reuse forever.
TEST(ManifoldReuse, BodyTurningPastTheThresholdGetsAFreshManifold) {
  FloorAndBox scene = MakeFloorAndBox(Settings(0.001), 0.0);
  for (int n = 0; n < 60; ++n) MustStep(scene.world);
  const double omega = 0.3e-3 / (kH * std::sqrt(3.0) / 2.0);
  ASSERT_TRUE(scene.world.SetAngularVelocity(scene.box, {0, omega, 0}));
  // The first step after the spin-up may still fall in the last cycle.
  int fresh = 0;
  int reused = 0;
  int run = 0;
  for (int n = 0; n < 120; ++n) {
    const StepStatistics stats = MustStep(scene.world);
    ASSERT_EQ(stats.manifolds, 1);
    if (stats.manifoldsReused == 0) {
      ++fresh;
      if (fresh > 1) {
        EXPECT_EQ(run, 3) << "step " << n;
      }
      run = 0;
    } else {
      ++reused;
      ++run;
    }
  }
  EXPECT_GE(fresh, 29);
  EXPECT_LE(fresh, 31);
  EXPECT_EQ(fresh + reused, 120);
  // The spin itself is untouched by the frictionless contact.
  EXPECT_NEAR(scene.world.GetBodyState(scene.box).Value().angularVelocity.y(), omega, 1e-9);

  // A fast turn (1 cm a step at the corners) never reuses.
  ASSERT_TRUE(scene.world.SetAngularVelocity(scene.box, {0, 100 * omega / 3, 0}));
  for (int n = 0; n < 10; ++n) EXPECT_EQ(MustStep(scene.world).manifoldsReused, 0);
}

// Both settings run the same pipeline up to the reuse test: with a reuse
// distance no moving pair can reach (1e-300 m) the anchors are recorded but
// not used, and the states must equal reuse off bit for bit, so recording
// has no effect on the physics and off is the narrow phase every step. A
// pair whose poses are bit-identical to the last narrow phase's (moved
// exactly 0 m, as a stack that has come to rest exactly can) is reused under
// any positive distance, so the two runs are compared in lockstep up to the
// first such step; the stack falls and lands for well over a second first.
TEST(ManifoldReuse, ReuseOffAndUnreachableReuseGiveBitIdenticalStates) {
  struct Scene {
    World world;
    std::vector<BodyId> bodies;
  };
  const auto make = [](double reuseDistance) {
    Scene scene{World::Create(Settings(reuseDistance)).Value(), {}};
    EXPECT_TRUE(scene.world.CreateBody(
        {.type = BodyType::Static, .position = {0, -0.5, 0}, .shape = Box({50, 0.5, 50})}));
    for (int i = 0; i < 6; ++i) {
      scene.bodies.push_back(scene.world
                                 .CreateBody({.type = BodyType::Dynamic,
                                              .position = {0.1 * i, 0.5 + 1.05 * i, 0.05 * i},
                                              .orientation = Quat(Eigen::AngleAxisd(0.2 * i, Vec3::UnitY())),
                                              .shape = Box({0.5, 0.5, 0.5}),
                                              .density = 1000.0})
                                 .Value());
    }
    return scene;
  };
  const auto state = [](const Scene& scene) {
    std::vector<double> values;
    for (const BodyId id : scene.bodies) {
      const BodyState s = scene.world.GetBodyState(id).Value();
      values.insert(values.end(), {s.position.x(), s.position.y(), s.position.z(), s.orientation.w(),
                                   s.orientation.x(), s.orientation.y(), s.orientation.z(),
                                   s.linearVelocity.x(), s.linearVelocity.y(), s.linearVelocity.z()});
    }
    return values;
  };
  Scene off = make(0.0);
  Scene unreachable = make(1e-300);
  int steps = 0;
  for (; steps < 240; ++steps) {
    MustStep(off.world);
    if (MustStep(unreachable.world).manifoldsReused > 0) break;
    ASSERT_EQ(state(off), state(unreachable)) << "step " << steps;
  }
  EXPECT_GE(steps, 90) << "a pair was reused before the stack came to rest";
}

// The anchors are kept beside the contacts, one entry per contact at the
// same index (world/world_data.h), so destroying a body must remove its
// contacts' anchors with them. Four boxes of different sizes rest apart on
// the floor; the first is destroyed, which moves every other pair's contact
// down one slot. Had the anchors not moved with them, each remaining pair
// would read a neighbour's, recorded at a pose metres away, and run the
// narrow phase instead of reusing (or, had the bound passed, rebuild points
// under the neighbour). So: all three pairs still reuse, and every rebuilt
// point lies under its own box.
TEST(ManifoldReuse, DestroyingABodyKeepsTheOtherPairsAnchorsWithTheirContacts) {
  World world = World::Create(Settings(kDefaultReuse)).Value();
  ASSERT_TRUE(
      world.CreateBody({.type = BodyType::Static, .position = {0, -0.5, 0}, .shape = Box({50, 0.5, 50})}));
  std::vector<BodyId> boxes;
  std::vector<Vec3> halves;
  for (int i = 0; i < 4; ++i) {
    const Vec3 half(0.3 + 0.1 * i, 0.25 + 0.05 * i, 0.4 - 0.05 * i);
    halves.push_back(half);
    boxes.push_back(world
                        .CreateBody({.type = BodyType::Dynamic,
                                     .position = {3.0 * i, half.y(), 0.5 * i},
                                     .shape = Box(half),
                                     .density = 1000.0})
                        .Value());
  }
  // One second: every box has settled and reuses its manifold.
  for (int n = 0; n < 60; ++n) MustStep(world);
  ASSERT_EQ(MustStep(world).manifoldsReused, 4);

  ASSERT_TRUE(world.DestroyBody(boxes[0]));
  const StepStatistics stats = MustStep(world);
  EXPECT_EQ(stats.manifolds, 3);
  EXPECT_EQ(stats.manifoldsReused, 3);
  const std::vector<ContactPointInfo> points = world.GetContactPoints();
  EXPECT_EQ(points.size(), 12u);  // four corners a box
  for (const ContactPointInfo& point : points) {
    const auto box =
        static_cast<std::size_t>(std::find(boxes.begin(), boxes.end(), point.bodyB) - boxes.begin());
    ASSERT_LT(box, boxes.size());
    ASSERT_NE(box, 0u);
    const Vec3 centre = world.GetBodyState(boxes[box]).Value().position;
    // A corner of the box's footprint on the floor: the box rests within
    // the Baumgarte slop (a few mm) of the floor and has not turned, so the
    // corner is within 1 mm of the footprint's corner in x and z.
    EXPECT_NEAR(std::abs(point.position.x() - centre.x()), halves[box].x(), 1e-3) << box;
    EXPECT_NEAR(std::abs(point.position.z() - centre.z()), halves[box].z(), 1e-3) << box;
    EXPECT_NEAR(point.position.y(), 0.0, 5e-3) << box;
  }
}

TEST(ManifoldReuse, BadReuseDistanceIsRefusedWithTheFieldNamed) {
  for (const double bad : {-1e-3, std::numeric_limits<double>::infinity(), std::nan("")}) {
    const Result<World> world = World::Create(Settings(bad));
    ASSERT_FALSE(world);
    EXPECT_NE(world.GetError().message.find("narrowPhase.reuseDistance"), std::string::npos);
  }
  EXPECT_TRUE(World::Create(Settings(0.0)));
  EXPECT_EQ(WorldSettings{}.methods.narrowPhase.reuseDistance, 0.0005);
}

}  // namespace manifold_reuse_world_test
}  // namespace talus
