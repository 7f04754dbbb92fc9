// Scenario files: the shipped ones load, sweeps expand, and every class of
// malformed file is refused with a message naming file, place and problem.
#include <gtest/gtest.h>

#include <string>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"

namespace talus::harness {
namespace scenario_loader_test {

const std::string kScenarioDir = TALUS_SCENARIO_DIR;
const std::string kBadDir = std::string(TALUS_TEST_DATA_DIR) + "/scenarios_bad/";

std::string LoadError(const std::string& name) {
  auto runs = LoadScenarioFile(kBadDir + name);
  EXPECT_FALSE(runs) << name << " was accepted";
  return runs ? std::string() : runs.GetError().message;
}

TEST(ScenarioLoader, EveryShippedScenarioLoads) {
  for (const char* file : {"/stacking/box_rest.json", "/sliding/box_slide.json",
                           "/bouncing/sphere_bounce.json", "/tumbling/box_free_fall.json"}) {
    auto runs = LoadScenarioFile(kScenarioDir + file);
    ASSERT_TRUE(runs) << runs.GetError().message;
    EXPECT_FALSE(runs.Value().empty());
  }
}

TEST(ScenarioLoader, BoxRestMapsEveryField) {
  auto runs = LoadScenarioFile(kScenarioDir + "/stacking/box_rest.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  ASSERT_EQ(runs.Value().size(), 1u);
  const harness::Run& run = runs.Value()[0];
  EXPECT_EQ(run.id, "box_rest");
  EXPECT_EQ(run.iterations, 10);
  EXPECT_EQ(run.steps, 180);  // 3 s at 60 Hz
  const Scenario& s = run.scenario;
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].motion, Motion::Static);
  EXPECT_EQ(std::get<BoxShape>(s.bodies[0].shape).halfExtents, Vec3(10, 0.5, 10));
  EXPECT_EQ(s.bodies[1].mass, 1.0);
  EXPECT_EQ(s.bodies[1].friction, 0.5);           // default
  EXPECT_EQ(s.world.gravity, Vec3(0, -9.81, 0));  // default
  EXPECT_EQ(s.world.frictionCombine, CombineRule::Sqrt);
  EXPECT_EQ(s.world.restitutionCombine, CombineRule::Max);
  EXPECT_TRUE(s.world.gyroscopic);  // default
  ASSERT_EQ(s.truths.size(), 1u);
  EXPECT_EQ(s.truths[0].body, 1);
  EXPECT_EQ(std::get<RestHeightTruth>(s.truths[0].kind).height, 0.5);
  EXPECT_EQ(s.truths[0].tolerance.absolute, 0.004);
}

TEST(ScenarioLoader, AxisAngleOrientationBecomesTheSameQuaternion) {
  auto runs = LoadScenarioFile(kScenarioDir + "/tumbling/box_free_fall.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  const Quat expected(Eigen::AngleAxisd(0.5, Vec3(1, 1, 0).normalized()));
  EXPECT_LT(runs.Value()[0].scenario.bodies[0].orientation.angularDistance(expected), 1e-15);
  EXPECT_EQ(runs.Value()[0].iterations, 0);  // "engine default"
}

TEST(ScenarioLoader, SweepExpandsToTheGridWithValuesWrittenIntoEveryTarget) {
  auto runs = LoadScenarioFile(kScenarioDir + "/sliding/box_slide.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  ASSERT_EQ(runs.Value().size(), 6u);         // 3 mu x 2 v0
  const harness::Run& run = runs.Value()[3];  // mu outermost: mu = 0.5, v0 = 3
  EXPECT_EQ(run.id, "box_slide[mu=0.5,v0=3]");
  ASSERT_EQ(run.sweepValues.size(), 2u);
  EXPECT_EQ(run.sweepValues[0].value, "0.5");
  EXPECT_EQ(run.scenario.bodies[0].friction, 0.5);
  EXPECT_EQ(run.scenario.bodies[1].friction, 0.5);
  EXPECT_EQ(run.scenario.bodies[1].linearVelocity.x(), 3.0);
  const auto& truth = std::get<SlidingStopTruth>(run.scenario.truths[0].kind);
  EXPECT_EQ(truth.mu, 0.5);
  EXPECT_EQ(truth.v0, 3.0);
  EXPECT_EQ(runs.Value()[0].id, "box_slide[mu=0.3,v0=1]");
}

TEST(ScenarioLoader, SyntaxErrorGivesFileLineAndColumn) {
  // The missing comma is noticed at the next token, "duration", which ends at column 40.
  const std::string message = LoadError("syntax_error.json");
  EXPECT_NE(message.find("syntax_error.json: line 3, column 40: syntax error"), std::string::npos) << message;
}

TEST(ScenarioLoader, UnknownFieldIsRefusedWithItsPointer) {
  const std::string message = LoadError("unknown_field.json");
  EXPECT_NE(message.find("/bodies/0/colour: unknown field"), std::string::npos) << message;
}

TEST(ScenarioLoader, WrongTypeNamesFieldAndTypes) {
  const std::string message = LoadError("wrong_type.json");
  EXPECT_NE(message.find("/world/timeStep: must be of type number, not string"), std::string::npos)
      << message;
}

TEST(ScenarioLoader, GyroscopicFlagIsRead) {
  auto runs = LoadScenarioFile(kScenarioDir + "/tumbling/box_intermediate_axis.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  EXPECT_TRUE(runs.Value()[0].scenario.world.gyroscopic);  // written explicitly
  auto off = ParseScenarioText(
      R"({"name": "x", "world": {"timeStep": 0.01, "duration": {"steps": 1}, "gyroscopic": false},
          "bodies": [{"name": "b", "shape": {"kind": "sphere", "radius": 1}, "motion": "static",
                      "position": [0, 0, 0]}]})",
      "off.json");
  ASSERT_TRUE(off) << off.GetError().message;
  EXPECT_FALSE(off.Value()[0].scenario.world.gyroscopic);
}

TEST(ScenarioLoader, GyroscopicFlagOfWrongTypeIsRefusedWithItsPointer) {
  const std::string message = LoadError("gyroscopic_wrong_type.json");
  EXPECT_NE(
      message.find("gyroscopic_wrong_type.json: /world/gyroscopic: must be of type boolean, not string"),
      std::string::npos)
      << message;
}

// A world with the given "broadPhase" entry (none when empty).
Result<std::vector<Run>> WithBroadPhase(const std::string& entry) {
  return ParseScenarioText(
      R"({"name": "x", "world": {"timeStep": 0.01, "duration": {"steps": 1})" + entry +
          R"(}, "bodies": [{"name": "b", "shape": {"kind": "sphere", "radius": 1}, "motion": "static",
                      "position": [0, 0, 0]}]})",
      "bp.json");
}

TEST(ScenarioLoader, BroadPhaseChoiceIsReadAndDefaultsToAuto) {
  auto none = WithBroadPhase("");
  ASSERT_TRUE(none) << none.GetError().message;
  EXPECT_EQ(none.Value()[0].scenario.world.broadPhase, BroadPhaseChoice::Auto);
  for (const BroadPhaseChoice choice : {BroadPhaseChoice::Auto, BroadPhaseChoice::UniformGrid,
                                        BroadPhaseChoice::AabbTree, BroadPhaseChoice::BruteForce}) {
    auto runs = WithBroadPhase(std::string(R"(, "broadPhase": ")") + BroadPhaseChoiceName(choice) + "\"");
    ASSERT_TRUE(runs) << runs.GetError().message;
    EXPECT_EQ(runs.Value()[0].scenario.world.broadPhase, choice) << BroadPhaseChoiceName(choice);
  }
  auto figure = LoadScenarioFile(kScenarioDir + "/tumbling/free_fall_15.json");
  ASSERT_TRUE(figure) << figure.GetError().message;
  EXPECT_EQ(figure.Value()[0].scenario.world.broadPhase, BroadPhaseChoice::UniformGrid);
}

TEST(ScenarioLoader, UnknownBroadPhaseIsRefusedWithItsPointerAndTheChoices) {
  for (const char* entry : {R"(, "broadPhase": "octree")", R"(, "broadPhase": "Uniform_Grid")",
                            R"(, "broadPhase": 1)", R"(, "broadPhase": "")"}) {
    auto runs = WithBroadPhase(entry);
    ASSERT_FALSE(runs) << entry;
    EXPECT_NE(
        runs.GetError().message.find(
            R"(bp.json: /world/broadPhase: must be one of ["auto","uniform_grid","aabb_tree","brute_force"])"),
        std::string::npos)
        << runs.GetError().message;
  }
}

TEST(ScenarioLoader, BounceTimingIsReadWrittenBackAndRefusedWhenUnknown) {
  auto none = WithBroadPhase("");
  ASSERT_TRUE(none) << none.GetError().message;
  EXPECT_EQ(none.Value()[0].scenario.world.bounceTiming, BounceTimingChoice::Auto);
  for (const BounceTimingChoice choice :
       {BounceTimingChoice::Auto, BounceTimingChoice::TimeOfImpact, BounceTimingChoice::StepBoundary}) {
    auto runs = WithBroadPhase(std::string(R"(, "bounceTiming": ")") + BounceTimingChoiceName(choice) + "\"");
    ASSERT_TRUE(runs) << runs.GetError().message;
    const Scenario& scenario = runs.Value()[0].scenario;
    EXPECT_EQ(scenario.world.bounceTiming, choice) << BounceTimingChoiceName(choice);
    // The writer's text reads back to the same choice.
    auto again = ParseScenarioText(ScenarioToJson(scenario), "again.json");
    ASSERT_TRUE(again) << again.GetError().message;
    EXPECT_EQ(again.Value()[0].scenario.world.bounceTiming, choice) << BounceTimingChoiceName(choice);
  }
  for (const char* entry : {R"(, "bounceTiming": "toi")", R"(, "bounceTiming": true)"}) {
    auto runs = WithBroadPhase(entry);
    ASSERT_FALSE(runs) << entry;
    EXPECT_NE(
        runs.GetError().message.find(
            R"(bp.json: /world/bounceTiming: must be one of ["auto","time_of_impact","step_boundary"])"),
        std::string::npos)
        << runs.GetError().message;
  }
}

TEST(ScenarioLoader, OutOfRangeNamesFieldAndBound) {
  const std::string message = LoadError("out_of_range.json");
  EXPECT_NE(message.find("out_of_range.json: /bodies/1/friction: must be >= 0"), std::string::npos)
      << message;
}

TEST(ScenarioLoader, MissingRequiredFieldIsNamed) {
  const std::string message = LoadError("missing_required.json");
  EXPECT_NE(message.find("/bodies/0: missing required field \"position\""), std::string::npos) << message;
}

TEST(ScenarioLoader, BothMassAndDensityAreRefused) {
  const std::string message = LoadError("mass_and_density.json");
  EXPECT_NE(message.find("/bodies/0: give either \"mass\" or \"density\", not both"), std::string::npos)
      << message;
}

TEST(ScenarioLoader, NonUnitQuaternionIsRefused) {
  const std::string message = LoadError("non_unit_quaternion.json");
  EXPECT_NE(message.find("/bodies/0/orientation/quaternion: quaternion is not unit length"),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, EmptyBodyListIsRefused) {
  const std::string message = LoadError("empty_bodies.json");
  EXPECT_NE(message.find("/bodies: needs at least 1 items"), std::string::npos) << message;
}

TEST(ScenarioLoader, ShapeFieldOfAnotherKindIsAnUnknownField) {
  const std::string message = LoadError("shape_field_of_other_kind.json");
  EXPECT_NE(message.find("/bodies/0/shape/radius: unknown field"), std::string::npos) << message;
}

TEST(ScenarioLoader, DuplicateBodyNameIsRefused) {
  const std::string message = LoadError("duplicate_body_name.json");
  EXPECT_NE(message.find("/bodies/1/name: duplicate body name \"box\""), std::string::npos) << message;
}

TEST(ScenarioLoader, TruthNamingAMissingBodyIsRefused) {
  const std::string message = LoadError("truth_unknown_body.json");
  EXPECT_NE(message.find("/truths/0/body: no body named \"crate\""), std::string::npos) << message;
}

// No truth without a tolerance: a truth without one used to be silently
// left out of the gate. The tolerance needs its physical reason beside it
// and must allow something; each refusal names the file and the field.
TEST(ScenarioLoader, TruthWithoutToleranceIsRefused) {
  const std::string message = LoadError("truth_without_tolerance.json");
  EXPECT_NE(message.find("truth_without_tolerance.json: /truths/0: missing required field \"tolerance\""),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, ToleranceWithoutReasonIsRefused) {
  const std::string message = LoadError("tolerance_without_reason.json");
  EXPECT_NE(
      message.find("tolerance_without_reason.json: /truths/0/tolerance: missing required field \"reason\""),
      std::string::npos)
      << message;
}

TEST(ScenarioLoader, ZeroToleranceIsRefused) {
  const std::string message = LoadError("tolerance_zero.json");
  EXPECT_NE(message.find("tolerance_zero.json: /truths/0/tolerance: needs absolute or relative > 0"),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, BackendUngatedTwiceIsRefused) {
  const std::string message = LoadError("ungated_backend_twice.json");
  EXPECT_NE(message.find("/truths/0/ungated/1/backend: backend \"talus-writeup\" is listed twice"),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, SweepTargetThatIsNotAFieldIsRefused) {
  const std::string message = LoadError("sweep_missing_target.json");
  EXPECT_NE(message.find("/sweeps/0/targets/0: \"/bodies/0/friction\" does not name a field"),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, SweepValueIsValidatedWhereItLands) {
  const std::string message = LoadError("sweep_value_out_of_range.json");
  EXPECT_NE(message.find("(mu=-1): /bodies/0/friction: must be >= 0"), std::string::npos) << message;
}

TEST(ScenarioLoader, DurationInBothFormsIsRefused) {
  const std::string message = LoadError("duration_both_forms.json");
  EXPECT_NE(message.find("/world/duration: matches more than one"), std::string::npos) << message;
}

TEST(ScenarioLoader, InfiniteNumberIsRefused) {
  const std::string message = LoadError("infinite_number.json");
  EXPECT_NE(message.find("infinite_number.json: number overflow parsing '1e999'"), std::string::npos)
      << message;
}

TEST(ScenarioLoader, MissingFileIsAnErrorNotACrash) {
  auto runs = LoadScenarioFile(kBadDir + "no_such_file.json");
  ASSERT_FALSE(runs);
  EXPECT_NE(runs.GetError().message.find("cannot open"), std::string::npos);
}

}  // namespace scenario_loader_test
}  // namespace talus::harness
