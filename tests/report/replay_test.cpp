// Replay recording and its JSON form: what the report's 3D view reads.
#include <gtest/gtest.h>

#include "report/report_html_replay.h"

#include "talus/harness/run/replay.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness {
namespace replay_test {

BackendRegistry MakeRegistry() {
  BackendRegistry registry;
  reference::RegisterTalusBackends(registry);
  return registry;
}

Run FreeFall15() {
  auto runs = LoadScenarios({std::filesystem::path(TALUS_SCENARIO_DIR) / "tumbling" / "free_fall_15.json"});
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs.Value().front();
}

TEST(Replay, OnlySelectedRunsRecordAReplay) {
  const harness::Run run = FreeFall15();
  RunnerOptions options;
  options.backends = {"talus"};
  options.deterministic = true;
  EXPECT_TRUE(RunOne(MakeRegistry(), run, "talus", options).replay.frames.empty());
  options.replay = {"free_fall_15"};
  EXPECT_FALSE(RunOne(MakeRegistry(), run, "talus", options).replay.frames.empty());
  EXPECT_TRUE(IsReplaySelected(run, {"all"}));
  EXPECT_TRUE(IsReplaySelected(run, {run.id}));
  EXPECT_FALSE(IsReplaySelected(run, {"box_rest"}));
}

TEST(Replay, FramesAreThinnedAndKeepTheFirstAndLastSample) {
  const harness::Run run = FreeFall15();
  RunnerOptions options;
  options.backends = {"talus"};
  options.replay = {"all"};
  options.replayFrames = 7;
  const RunResult result = RunOne(MakeRegistry(), run, "talus", options);
  ASSERT_EQ(result.replay.frames.size(), 7u);
  EXPECT_EQ(result.replay.frames.front().time, 0.0);
  EXPECT_DOUBLE_EQ(result.replay.frames.back().time, run.steps * run.timeStep);
  ASSERT_EQ(result.replay.shapes.size(), 15u);
  for (const ReplayFrame& frame : result.replay.frames) {
    EXPECT_EQ(frame.positions.size(), 15u);
    EXPECT_EQ(frame.orientations.size(), 15u);
  }
}

// The write-up's figure-2 funnel on its 15-body scene: the grid meets more
// pairs than have touching spheres, and none of the cubes (0.3 m apart)
// touch, so the funnel ends at zero while SAT tests are run. The scenario
// forces the grid (world.broadPhase), and the counters say it ran.
TEST(Replay, TalusCountersShowTheBroadPhaseFunnelForFifteenFallingCubes) {
  const harness::Run run = FreeFall15();
  ASSERT_EQ(run.scenario.world.broadPhase, BroadPhaseChoice::UniformGrid);
  RunnerOptions options;
  // talus-writeup keeps the write-up's fixed 2 cm speculative margin, so the
  // spheres are the shapes' own plus 2 cm; talus grows them by each body's
  // reach this step (MethodSettings::speculativeMotion, the next test).
  options.backends = {"talus-writeup"};
  options.replay = {"all"};
  const RunResult result = RunOne(MakeRegistry(), run, "talus-writeup", options);
  const std::vector<std::string> expected = {"bodies",
                                             "candidate pairs",
                                             "sphere pairs",
                                             "SAT tests",
                                             "intersecting pairs",
                                             "contact points",
                                             "structure: uniform grid",
                                             "structure: AABB tree",
                                             "structure: brute force"};
  ASSERT_EQ(result.replay.counterNames, expected);
  EXPECT_EQ(StructureThatRan(result.replay),
            "uniform grid in all " + std::to_string(result.replay.frames.size() - 1) + " recorded steps");
  // The grid's cells (one per sphere diameter) keep it from meeting all
  // 15 * 14 / 2 = 105 pairs, which brute force meets.
  EXPECT_LT(result.replay.frames.back().counters[1], 105.0);
  const ReplayFrame& last = result.replay.frames.back();
  ASSERT_EQ(last.counters.size(), expected.size());
  EXPECT_EQ(last.counters[0], 15.0);
  // Cubes 0.8 m apart along x and z in a row: 3 x 5 layers give 2 * 5 pairs
  // along x within a row plus 3 * 2 along z between rows of equal height
  // (1.6 m apart, beyond the 0.866 m sphere reach): exactly 10 touching spheres.
  EXPECT_EQ(last.counters[2], 10.0);
  EXPECT_GE(last.counters[1], last.counters[2]);
  EXPECT_GE(last.counters[2], last.counters[4]);
  EXPECT_EQ(last.counters[4], 0.0);
  EXPECT_EQ(last.counters[5], 0.0);
  EXPECT_TRUE(last.contacts.empty());
}

// talus's spheres grow by each body's reach this step (here the fall speed
// times h), so more of them touch than the fixed margin's 10; but the
// cubes fall side by side, nothing closes on anything, and the narrow
// phase's pair margins (relative motion) leave them apart: no contact.
TEST(Replay, TalusSpheresGrowWithTheFallButNoPairCloses) {
  const harness::Run run = FreeFall15();
  RunnerOptions options;
  options.backends = {"talus"};
  options.replay = {"all"};
  const RunResult result = RunOne(MakeRegistry(), run, "talus", options);
  const ReplayFrame& last = result.replay.frames.back();
  EXPECT_GT(last.counters[2], 10.0);
  EXPECT_EQ(last.counters[4], 0.0);
  EXPECT_EQ(last.counters[5], 0.0);
  EXPECT_TRUE(last.contacts.empty());
}

// Without the forcing, a world of 15 bodies takes brute force: every pair
// is a candidate, and the pairs found are the same.
TEST(Replay, AutoBroadPhaseRunsBruteForceOnFifteenCubesWithTheSamePairs) {
  harness::Run run = FreeFall15();
  run.scenario.world.broadPhase = BroadPhaseChoice::Auto;
  RunnerOptions options;
  options.backends = {"talus-writeup"};  // the fixed margin, as above
  options.replay = {"all"};
  const RunResult result = RunOne(MakeRegistry(), run, "talus-writeup", options);
  EXPECT_EQ(StructureThatRan(result.replay),
            "brute force in all " + std::to_string(result.replay.frames.size() - 1) + " recorded steps");
  const ReplayFrame& last = result.replay.frames.back();
  EXPECT_EQ(last.counters[1], 105.0);
  EXPECT_EQ(last.counters[2], 10.0);
}

TEST(Replay, JsonRoundTripIsExactAndDeterministic) {
  const harness::Run run = FreeFall15();
  RunnerOptions options;
  options.backends = {"talus"};
  options.replay = {"all"};
  options.replayFrames = 5;
  options.deterministic = true;
  ResultsFile file;
  file.backends = {"talus"};
  file.deterministic = true;
  file.results.push_back(RunOne(MakeRegistry(), run, "talus", options));
  const std::string text = ResultsToJson(file);
  auto read = ResultsFromJson(text);
  ASSERT_TRUE(read) << read.GetError().message;
  EXPECT_EQ(ResultsToJson(read.Value()), text);
  file.results[0] = RunOne(MakeRegistry(), run, "talus", options);
  EXPECT_EQ(ResultsToJson(file), text);
}

TEST(Replay, ContactsAreRecordedWithBodiesAndUnitNormals) {
  auto runs = LoadScenarios({std::filesystem::path(TALUS_SCENARIO_DIR) / "stacking" / "box_rest.json"});
  ASSERT_TRUE(runs) << runs.GetError().message;
  RunnerOptions options;
  options.backends = {"talus"};
  options.replay = {"all"};
  const RunResult result = RunOne(MakeRegistry(), runs.Value().front(), "talus", options);
  const ReplayFrame& last = result.replay.frames.back();
  ASSERT_FALSE(last.contacts.empty());
  for (const ContactReading& c : last.contacts) {
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-9);  // unit by contract; rounding only
    EXPECT_NE(c.bodyA, c.bodyB);
  }
}

TEST(Replay, HullShapesCarryTheirFacesAndBadJsonIsReportedWithItsPlace) {
  BodySpec body;
  body.name = "tetra";
  body.shape = HullShape{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}};
  auto shape = MakeReplayShape(body);
  ASSERT_TRUE(shape) << shape.GetError().message;
  EXPECT_EQ(shape.Value().vertices.size(), 4u);
  EXPECT_EQ(shape.Value().faces.size(), 4u);

  body.shape = HullShape{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}};
  auto flat = MakeReplayShape(body);
  ASSERT_FALSE(flat);
  EXPECT_NE(flat.GetError().message.find("tetra"), std::string::npos);

  Replay replay;
  replay.shapes.push_back(shape.Value());
  replay.frames.push_back({0.0, {Vec3::Zero()}, {Quat::Identity()}, {}, {}});
  nlohmann::ordered_json json = ReplayToJson(replay);
  json["frames"][0]["q"][0] = {1, 0, 0};
  auto bad = ReplayFromJson(json, "/results/0/replay");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.GetError().message.rfind("/results/0/replay/frames/0/q", 0), 0u) << bad.GetError().message;
}

}  // namespace replay_test
}  // namespace talus::harness
