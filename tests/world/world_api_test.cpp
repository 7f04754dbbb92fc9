// The World's boundary: ids, bad input refused with the world unchanged,
// settings validation.
#include <gtest/gtest.h>

#include <limits>

#include "support/same_bits.h"
#include "talus/world.h"

namespace talus {
namespace world_api_test {

using testing_support::SameBits;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(WorldApi, CreatedBodyReportsItsDefinition) {
  World world;
  const BodyId id = world
                        .CreateBody({.type = BodyType::Dynamic,
                                     .position = {0, 4, 0},
                                     .linearVelocity = {1, 2, 3},
                                     .mass = 2.5,
                                     .localCenterOfMass = {0.1, 0, 0}})
                        .Value();
  const BodyState s = world.GetBodyState(id).Value();
  EXPECT_EQ(s.type, BodyType::Dynamic);
  EXPECT_EQ(s.position, Vec3(0, 4, 0));
  EXPECT_EQ(s.centerOfMass, Vec3(0.1, 4, 0));
  EXPECT_EQ(s.linearVelocity, Vec3(1, 2, 3));
  EXPECT_EQ(s.mass, 2.5);
  EXPECT_EQ(world.BodyCount(), 1);
}

TEST(WorldApi, StaleIdIsDetectedAfterDestroyAndSlotReuse) {
  World world;
  const BodyId first = world.CreateBody({.type = BodyType::Dynamic}).Value();
  ASSERT_TRUE(world.DestroyBody(first));
  EXPECT_FALSE(world.IsValid(first));
  // The slot is reused with a new generation: the old id still fails.
  const BodyId second = world.CreateBody({.type = BodyType::Dynamic}).Value();
  EXPECT_EQ(second.index, first.index);
  EXPECT_NE(second.generation, first.generation);
  EXPECT_FALSE(world.GetBodyState(first));
  EXPECT_FALSE(world.DestroyBody(first));
  EXPECT_FALSE(world.ApplyForceToCenter(first, {1, 0, 0}));
  EXPECT_FALSE(world.SetLinearVelocity(first, {1, 0, 0}));
  EXPECT_TRUE(world.IsValid(second));
  EXPECT_FALSE(world.IsValid(BodyId{}));
  EXPECT_FALSE(world.IsValid(BodyId{.index = 99, .generation = 0}));
  EXPECT_NE(world.GetBodyState(first).GetError().message.find("does not name a live body"),
            std::string::npos);
}

TEST(WorldApi, BadBodyDefinitionsAreRefusedWithTheFieldNamed) {
  World world;
  const struct {
    BodyDef def;
    const char* field;
  } cases[] = {
      {{.type = BodyType::Dynamic, .position = {kNaN, 0, 0}}, "position"},
      {{.type = BodyType::Dynamic, .orientation = Quat(0, 0, 0, 0)}, "orientation"},
      {{.type = BodyType::Dynamic, .linearVelocity = {0, kInf, 0}}, "linearVelocity"},
      {{.type = BodyType::Dynamic, .angularVelocity = {0, 0, kNaN}}, "angularVelocity"},
      {{.type = BodyType::Dynamic, .mass = 0.0}, "mass"},
      {{.type = BodyType::Dynamic, .mass = -1.0}, "mass"},
      {{.type = BodyType::Dynamic, .mass = kNaN}, "mass"},
      {{.type = BodyType::Dynamic, .localInertia = -Mat3::Identity()}, "localInertia"},
      {{.type = BodyType::Dynamic, .localInertia = Mat3::Zero()}, "localInertia"},
      {{.type = BodyType::Dynamic, .friction = -0.1}, "friction"},
      {{.type = BodyType::Dynamic, .restitution = 1.5}, "restitution"},
  };
  for (const auto& c : cases) {
    const auto result = world.CreateBody(c.def);
    ASSERT_FALSE(result) << c.field;
    EXPECT_NE(result.GetError().message.find(c.field), std::string::npos) << result.GetError().message;
  }
  EXPECT_EQ(world.BodyCount(), 0);
  // A static body ignores mass: zero is fine there.
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static, .mass = 0.0}));
}

TEST(WorldApi, BadStepAndBadForcesLeaveTheWorldUnchanged) {
  World world;
  const BodyId id =
      world.CreateBody({.type = BodyType::Dynamic, .position = {0, 4, 0}, .angularVelocity = {0, 1, 0}})
          .Value();
  ASSERT_TRUE(world.Step(1.0 / 60.0));
  const BodyState before = world.GetBodyState(id).Value();
  EXPECT_FALSE(world.Step(0.0));
  EXPECT_FALSE(world.Step(-1.0 / 60.0));
  EXPECT_FALSE(world.Step(kNaN));
  EXPECT_FALSE(world.Step(kInf));
  EXPECT_FALSE(world.ApplyForceToCenter(id, {kNaN, 0, 0}));
  EXPECT_FALSE(world.ApplyForce(id, {1, 0, 0}, {0, kInf, 0}));
  EXPECT_FALSE(world.ApplyTorque(id, {0, kInf, 0}));
  EXPECT_FALSE(world.ApplyLinearImpulse(id, {0, kNaN, 0}, {0, 0, 0}));
  EXPECT_FALSE(world.ApplyAngularImpulse(id, {kNaN, 0, 0}));
  EXPECT_FALSE(world.SetLinearVelocity(id, {kInf, 0, 0}));
  EXPECT_FALSE(world.SetAngularVelocity(id, {kNaN, 0, 0}));
  EXPECT_FALSE(world.SetTransform(id, {kNaN, 0, 0}, Quat::Identity()));
  EXPECT_FALSE(world.SetTransform(id, {0, 0, 0}, Quat(0, 0, 0, 0)));
  // Finite but overflowing: 1.8e308 N s applied 4 m below the centre gives
  // an infinite angular velocity, so it is refused like a NaN.
  const double huge = std::numeric_limits<double>::max();
  EXPECT_FALSE(world.ApplyLinearImpulse(id, {huge, 0, 0}, {0, 0, 0}));
  EXPECT_TRUE(SameBits(before, world.GetBodyState(id).Value()));
  const auto message = world.Step(-1.0).GetError().message;
  EXPECT_NE(message.find("dt"), std::string::npos) << message;

  // The world keeps running, and refused forces left nothing behind: the
  // next step matches a twin world that never saw the bad calls.
  World twin;
  const BodyId twinId =
      twin.CreateBody({.type = BodyType::Dynamic, .position = {0, 4, 0}, .angularVelocity = {0, 1, 0}})
          .Value();
  ASSERT_TRUE(twin.Step(1.0 / 60.0));
  ASSERT_TRUE(world.Step(1.0 / 60.0));
  ASSERT_TRUE(twin.Step(1.0 / 60.0));
  EXPECT_TRUE(SameBits(world.GetBodyState(id).Value(), twin.GetBodyState(twinId).Value()));
}

TEST(WorldApi, InvalidSettingsAreRefusedAndTheOldOnesKept) {
  World world;
  EXPECT_FALSE(world.SetSettings({.velocityIterations = 0}));
  EXPECT_FALSE(world.SetSettings({.baumgarte = 1.5}));
  EXPECT_FALSE(world.SetSettings({.slop = -0.1}));
  EXPECT_FALSE(world.SetSettings({.gravity = {0, kNaN, 0}}));
  EXPECT_FALSE(world.SetSettings({.restitutionThreshold = kNaN}));
  EXPECT_FALSE(World::Create({.timeToSleep = -1.0}));
  EXPECT_EQ(world.Settings().velocityIterations, WorldSettings{}.velocityIterations);
  const auto result = world.SetSettings({.baumgarte = 2.0});
  EXPECT_NE(result.GetError().message.find("baumgarte"), std::string::npos);
}

TEST(WorldApi, ForcesAndImpulsesChangeMomentumAsNewtonSays) {
  World world = World::Create({.gravity = Vec3::Zero(), .sleeping = false}).Value();
  const BodyId id = world.CreateBody({.type = BodyType::Dynamic, .mass = 2.0}).Value();
  ASSERT_TRUE(world.ApplyForceToCenter(id, {4, 0, 0}));
  ASSERT_TRUE(world.Step(0.5));
  // dv = F h / m = 4 * 0.5 / 2 = 1 m/s; the force lasts one step only.
  EXPECT_DOUBLE_EQ(world.GetBodyState(id).Value().linearVelocity.x(), 1.0);
  ASSERT_TRUE(world.Step(0.5));
  EXPECT_DOUBLE_EQ(world.GetBodyState(id).Value().linearVelocity.x(), 1.0);
  ASSERT_TRUE(world.ApplyLinearImpulse(id, {0, 2, 0}, world.GetBodyState(id).Value().centerOfMass));
  EXPECT_DOUBLE_EQ(world.GetBodyState(id).Value().linearVelocity.y(), 1.0);
  // An off-centre impulse also spins the body: dw = I^-1 (r x J), with the
  // default inertia I = 1/6 kg m^2 on each axis (not scaled by mass).
  ASSERT_TRUE(
      world.ApplyLinearImpulse(id, {0, 0, 1}, world.GetBodyState(id).Value().centerOfMass + Vec3(1, 0, 0)));
  const Vec3 w = world.GetBodyState(id).Value().angularVelocity;
  EXPECT_NEAR(w.y(), -6.0, 1e-12);
  EXPECT_NEAR(w.x(), 0.0, 1e-12);
}

TEST(WorldApi, StaticAndKinematicBodiesIgnoreForces) {
  World world;
  const BodyId ground = world.CreateBody({.type = BodyType::Static}).Value();
  const BodyId lift = world.CreateBody({.type = BodyType::Kinematic, .linearVelocity = {0, 1, 0}}).Value();
  ASSERT_TRUE(world.ApplyForceToCenter(ground, {0, 100, 0}));
  ASSERT_TRUE(world.ApplyForceToCenter(lift, {0, -100, 0}));
  for (int n = 0; n < 60; ++n) ASSERT_TRUE(world.Step(1.0 / 60.0));
  EXPECT_EQ(world.GetBodyState(ground).Value().position, Vec3::Zero());
  // The kinematic body moves with its velocity only: 1 m in 1 s, no gravity.
  EXPECT_NEAR(world.GetBodyState(lift).Value().position.y(), 1.0, 1e-12);
  EXPECT_EQ(world.GetBodyState(lift).Value().linearVelocity, Vec3(0, 1, 0));
}

// StepStatistics::seconds is filled only when WorldSettings::timeStages is
// on; then every stage that ran took some time and the total is their sum.
// Off, the same step leaves every field 0 and the physics is the same bits.
TEST(WorldApi, StageTimesAreFilledOnlyWhenAskedFor) {
  BodyState states[2];
  for (const bool timed : {false, true}) {
    World world = World::Create({.timeStages = timed}).Value();
    ASSERT_TRUE(world.CreateBody({.type = BodyType::Static, .shape = Shape::CreateBox({5, 0.5, 5}).Value()}));
    const BodyId box = world
                           .CreateBody({.type = BodyType::Dynamic,
                                        .position = {0, 0.7, 0},
                                        .shape = Shape::CreateBox({0.2, 0.2, 0.2}).Value()})
                           .Value();
    StepStatistics last;
    for (int n = 0; n < 30; ++n) last = world.Step(1.0 / 60.0).Value();
    const StageTimes& t = last.seconds;
    double sum = 0.0;
    for (const StageInfo& stage : kStages) sum += t[stage.stage];
    if (timed) {
      EXPECT_GT(t[Stage::FindContacts], 0.0);
      EXPECT_GT(t[Stage::SolveVelocities], 0.0);
      EXPECT_EQ(t.total, sum);
    } else {
      EXPECT_EQ(sum, 0.0);
      EXPECT_EQ(t.total, 0.0);
    }
    states[timed ? 1 : 0] = world.GetBodyState(box).Value();
  }
  EXPECT_EQ(states[0].position, states[1].position);
  EXPECT_EQ(states[0].orientation.coeffs(), states[1].orientation.coeffs());
}

}  // namespace world_api_test
}  // namespace talus
