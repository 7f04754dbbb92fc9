// The scenario language's loads, impulses and kinematic bodies
// (docs/scenarios.md, "Loads, impulses and kinematic bodies"): read into
// the model, written back by the writer to the same model, refused with the
// field and the reason when wrong, and scheduled over the steps so that the
// impulse a load delivers is exact at any time step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "talus/harness/scenario/applied_loads.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"

namespace talus::harness {
namespace scenario_loads_test {

// A 1 s run at 0.01 s (100 steps) with a ground, a box, a platform and
// whatever `extra` adds at the top level (loads, impulses).
std::string Scene(const std::string& extra, const std::string& platform = R"("motion": "kinematic",
      "linearVelocity": [1, 0, 0], "angularVelocity": [0, 0.5, 0])") {
  return R"({"name": "loads", "world": {"timeStep": 0.01, "duration": {"seconds": 1}},
  "bodies": [
    {"name": "ground", "shape": {"kind": "box", "halfExtents": [5, 0.5, 5]}, "motion": "static",
     "position": [0, -0.5, 0]},
    {"name": "box", "shape": {"kind": "box", "halfExtents": [0.5, 0.5, 0.5]}, "motion": "dynamic",
     "position": [0, 2, 0], "mass": 2},
    {"name": "platform", "shape": {"kind": "box", "halfExtents": [1, 0.1, 1]}, )" +
         platform + R"(, "position": [0, 5, 0]}
  ])" + extra +
         "}";
}

Scenario Load(const std::string& text) {
  auto runs = ParseScenarioText(text, "loads.json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value()[0].scenario : Scenario{};
}

std::string Refusal(const std::string& text) {
  auto runs = ParseScenarioText(text, "loads.json");
  EXPECT_FALSE(runs) << "accepted: " << text;
  return runs ? std::string() : runs.GetError().message;
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ScenarioLoads, AreReadIntoTheModel) {
  const Scenario s = Load(Scene(R"(, "loads": [
    {"body": "box", "force": [3, 0, 0], "at": [0, 0.5, 0], "start": 0.25, "end": 0.75},
    {"body": "box", "torque": [0, 0, 2], "frame": "body"}],
  "impulses": [{"body": "box", "linear": [0, 1, 0], "at": [0.5, 0, 0], "time": 0.5}])"));
  ASSERT_EQ(s.loads.size(), 2u);
  EXPECT_EQ(s.loads[0].body, 1);
  EXPECT_EQ(s.loads[0].force, Vec3(3, 0, 0));
  EXPECT_EQ(s.loads[0].torque, Vec3::Zero());
  EXPECT_EQ(s.loads[0].frame, LoadFrame::World);
  ASSERT_TRUE(s.loads[0].point);
  EXPECT_EQ(*s.loads[0].point, Vec3(0, 0.5, 0));
  EXPECT_EQ(s.loads[0].start, 0.25);
  EXPECT_EQ(s.loads[0].end, 0.75);
  EXPECT_EQ(s.loads[1].frame, LoadFrame::Body);
  EXPECT_EQ(s.loads[1].start, 0.0);
  EXPECT_TRUE(std::isinf(s.loads[1].end));  // to the run's end
  EXPECT_FALSE(s.loads[1].point);
  ASSERT_EQ(s.impulses.size(), 1u);
  EXPECT_EQ(s.impulses[0].linear, Vec3(0, 1, 0));
  EXPECT_EQ(s.impulses[0].time, 0.5);
  EXPECT_EQ(s.bodies[2].motion, Motion::Kinematic);
  EXPECT_EQ(s.bodies[2].linearVelocity, Vec3(1, 0, 0));
  EXPECT_EQ(s.bodies[2].angularVelocity, Vec3(0, 0.5, 0));
}

TEST(ScenarioLoads, TheWriterWritesTheSameModelBack) {
  const Scenario s = Load(Scene(R"(, "loads": [
    {"body": "box", "force": [3, 0, 0], "at": [0, 0.5, 0], "start": 0.25, "end": 0.75},
    {"body": "box", "torque": [0, 0, 2], "frame": "body"}],
  "impulses": [{"body": "box", "linear": [0, 1, 0], "at": [0.5, 0, 0], "time": 0.5},
               {"body": "box", "linear": [1, 0, 0]}])"));
  const Scenario again = Load(ScenarioToJson(s));
  EXPECT_EQ(again.loads, s.loads);
  EXPECT_EQ(again.impulses, s.impulses);
  ASSERT_EQ(again.bodies.size(), 3u);
  EXPECT_EQ(again.bodies[2].motion, Motion::Kinematic);
  EXPECT_EQ(again.bodies[2].linearVelocity, s.bodies[2].linearVelocity);
  EXPECT_EQ(again.bodies[2].angularVelocity, s.bodies[2].angularVelocity);
  // And the text is a fixed point: written twice, the same bytes.
  EXPECT_EQ(ScenarioToJson(again), ScenarioToJson(s));
}

TEST(ScenarioLoads, BadLoadsAreRefusedNamingTheFieldAndWhy) {
  std::string m = Refusal(Scene(R"(, "loads": [{"body": "crate", "force": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/loads/0/body") && Has(m, "no body named \"crate\"")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "ground", "force": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/loads/0/body") && Has(m, "\"ground\" is static") && Has(m, "dynamic")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "platform", "force": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/loads/0/body") && Has(m, "\"platform\" is kinematic")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box"}])"));
  EXPECT_TRUE(Has(m, "/loads/0") && Has(m, "needs \"force\", \"torque\" or both")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "torque": [1, 0, 0], "at": [0, 1, 0]}])"));
  EXPECT_TRUE(Has(m, "/loads/0/at") && Has(m, "needs a \"force\"")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "start": 0.5, "end": 0.5}])"));
  EXPECT_TRUE(Has(m, "/loads/0/end") && Has(m, "not after its start at 0.5 s")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "start": 0.5, "end": 0.25}])"));
  EXPECT_TRUE(Has(m, "/loads/0/end") && Has(m, "ends at 0.25 s")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "end": 2}])"));
  EXPECT_TRUE(Has(m, "/loads/0/end") && Has(m, "after the run ends at 1 s")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "start": 1}])"));
  EXPECT_TRUE(Has(m, "/loads/0/start") && Has(m, "never act")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "start": -1}])"));
  EXPECT_TRUE(Has(m, "/loads/0/start") && Has(m, "must be >= 0")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1e999, 0, 0]}])"));
  // JSON has no NaN or infinity; a number too large for a double is refused as it is read.
  EXPECT_TRUE(Has(m, "number overflow parsing '1e999'")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "frame": "local"}])"));
  EXPECT_TRUE(Has(m, "/loads/0/frame") && Has(m, "must be one of")) << m;
  m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "at": [0, 2e9, 0]}])"));
  EXPECT_TRUE(Has(m, "/loads/0/at") && Has(m, "beyond the limit")) << m;
  // The end exactly at the run's end (the default's value written out) is fine.
  EXPECT_EQ(Load(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "end": 1}])")).loads[0].end, 1.0);
}

TEST(ScenarioLoads, BadImpulsesAreRefusedNamingTheFieldAndWhy) {
  std::string m = Refusal(Scene(R"(, "impulses": [{"body": "ground", "linear": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/impulses/0/body") && Has(m, "\"ground\" is static") && Has(m, "an impulse")) << m;
  m = Refusal(Scene(R"(, "impulses": [{"body": "platform", "linear": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/impulses/0/body") && Has(m, "kinematic")) << m;
  m = Refusal(Scene(R"(, "impulses": [{"body": "nobody", "linear": [1, 0, 0]}])"));
  EXPECT_TRUE(Has(m, "/impulses/0/body") && Has(m, "no body named \"nobody\"")) << m;
  m = Refusal(Scene(R"(, "impulses": [{"body": "box"}])"));
  EXPECT_TRUE(Has(m, "/impulses/0") && Has(m, "missing required field \"linear\"")) << m;
  m = Refusal(Scene(R"(, "impulses": [{"body": "box", "linear": [1, 0, 0], "time": 0.999}])"));
  EXPECT_TRUE(Has(m, "/impulses/0/time") && Has(m, "not before the run's last step, at 0.99 s")) << m;
  m = Refusal(Scene(R"(, "impulses": [{"body": "box", "linear": [1, 1e999, 0]}])"));
  EXPECT_TRUE(Has(m, "number overflow parsing '1e999'")) << m;
}

TEST(ScenarioLoads, AKinematicBodyTakesVelocitiesButNoMass) {
  std::string m = Refusal(Scene("", R"("motion": "kinematic", "mass": 3)"));
  EXPECT_TRUE(Has(m, "/bodies/2/mass") && Has(m, "a kinematic body takes no mass")) << m;
  m = Refusal(Scene("", R"("motion": "kinematic", "density": 3)"));
  EXPECT_TRUE(Has(m, "/bodies/2/density") && Has(m, "infinite mass")) << m;
  m = Refusal(Scene("", R"("motion": "kinematic", "linearVelocity": [1e300, 0, 0])"));
  EXPECT_TRUE(Has(m, "/bodies/2/linearVelocity") && Has(m, "speed of light")) << m;
  // A static body still may not move.
  m = Refusal(Scene("", R"("motion": "static", "linearVelocity": [1, 0, 0])"));
  EXPECT_TRUE(Has(m, "/bodies/2") && Has(m, "a static body cannot move")) << m;
  // Without velocities a kinematic body stands still.
  EXPECT_EQ(Load(Scene("", R"("motion": "kinematic")")).bodies[2].linearVelocity, Vec3::Zero());
}

TEST(ScenarioLoads, ASweepCannotSmuggleInABadWindow) {
  const std::string m = Refusal(Scene(R"(, "loads": [{"body": "box", "force": [1, 0, 0], "end": 0.5}],
    "sweeps": [{"name": "end", "targets": ["/loads/0/end"], "values": [0.5, 0]}])"));
  EXPECT_TRUE(Has(m, "(end=0)") && Has(m, "/loads/0/end")) << m;
}

TEST(AppliedLoadShare, DeliversExactlyForceTimesWindowAtAnyStep) {
  // The shares of the steps sum to the window's length over h (to
  // round-off, ~1e-15 per step), whether or not the window's edges fall
  // on step boundaries; a window inside one step gets its fraction.
  AppliedLoad load;
  load.start = 0.123;
  load.end = 0.7071;
  for (const double h : {0.01, 1.0 / 60.0, 0.0137, 0.5}) {
    double sum = 0.0;
    for (long long k = 0; k * h < 1.0; ++k) sum += AppliedLoadShare(load, k * h, h) * h;
    EXPECT_NEAR(sum, load.end - load.start, 1e-12) << "h " << h;
  }
  load.start = 0.101;
  load.end = 0.102;
  EXPECT_NEAR(AppliedLoadShare(load, 0.1, 0.01), 0.1, 1e-12);
  EXPECT_EQ(AppliedLoadShare(load, 0.11, 0.01), 0.0);
  // Open-ended: every step from the start on is whole.
  AppliedLoad always;
  EXPECT_EQ(AppliedLoadShare(always, 0.0, 0.01), 1.0);
  EXPECT_EQ(AppliedLoadShare(always, 1e6, 0.01), 1.0);
}

TEST(AppliedLoadShare, BodyFrameVectorsTurnWithTheBody) {
  AppliedLoad load;
  load.force = Vec3(1, 0, 0);
  load.torque = Vec3(0, 2, 0);
  load.point = Vec3(0, 0, 1);
  load.frame = LoadFrame::Body;
  const Quat quarterTurnAboutY(Eigen::AngleAxisd(std::acos(-1.0) / 2.0, Vec3::UnitY()));
  const WorldLoad w = ToWorldLoad(load, 0.5, Vec3(10, 0, 0), quarterTurnAboutY);
  // Body x turned a quarter about y is world -z; body z is world x.
  EXPECT_LT((w.force - Vec3(0, 0, -0.5)).norm(), 1e-15);
  EXPECT_LT((w.torque - Vec3(0, 1, 0)).norm(), 1e-15);
  ASSERT_TRUE(w.point);
  EXPECT_LT((*w.point - Vec3(11, 0, 0)).norm(), 1e-15);
  load.frame = LoadFrame::World;
  const WorldLoad fixed = ToWorldLoad(load, 1.0, Vec3::Zero(), quarterTurnAboutY);
  EXPECT_EQ(fixed.force, Vec3(1, 0, 0));
  // The point is in the body frame whatever the vectors' frame.
  EXPECT_LT((*fixed.point - Vec3(1, 0, 0)).norm(), 1e-15);
}

TEST(AppliedImpulseAtStep, IsTheStepNearestItsTime) {
  AppliedImpulse impulse;
  EXPECT_TRUE(AppliedImpulseAtStep(impulse, 0, 0.01));
  EXPECT_FALSE(AppliedImpulseAtStep(impulse, 1, 0.01));
  impulse.time = 0.5;
  EXPECT_TRUE(AppliedImpulseAtStep(impulse, 50, 0.01));
  EXPECT_TRUE(AppliedImpulseAtStep(impulse, 30, 1.0 / 60.0));
  EXPECT_FALSE(AppliedImpulseAtStep(impulse, 49, 0.01));
}

}  // namespace scenario_loads_test
}  // namespace talus::harness
