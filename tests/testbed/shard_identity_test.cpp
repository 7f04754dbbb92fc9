// The merge refuses shards that are not of one partition (harness sweep.h):
// missing, repeated, from another build, with other settings, or over
// another scenario set or other scenario contents, each named in the
// message. Shards here are made by hand (one result per run), so only the
// checks run, not the engines.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/support/build_id.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {
namespace shard_identity_test {

// The runs of box_free_fall and box_rest at two time steps.
std::vector<harness::Run> TwoScenarioRuns() {
  std::vector<harness::Run> runs;
  for (const char* file : {"/tumbling/box_free_fall.json", "/stacking/box_rest.json"}) {
    auto loaded = LoadScenarioFile(std::string(TALUS_SCENARIO_DIR) + file);
    EXPECT_TRUE(loaded) << loaded.GetError().message;
    for (const harness::Run& run : loaded.Value()) runs.push_back(run);
  }
  auto expanded = ExpandStepping(runs, {1.0 / 30.0, 1.0 / 60.0}, {10});
  EXPECT_TRUE(expanded);
  return expanded.Value();
}

// Shard `index` of `count` over `runs`, one (empty) result per run.
ShardFile MakeShard(const std::vector<harness::Run>& runs, int index, int count) {
  ShardFile shard;
  shard.shard = {index, count};
  shard.identity = MakeShardIdentity(runs, {1.0 / 30.0, 1.0 / 60.0}, {10});
  shard.runCount = static_cast<int>(runs.size());
  shard.runIndices = ShardRuns(shard.runCount, shard.shard);
  shard.results.backends = {"talus"};
  shard.results.deterministic = true;
  for (int r : shard.runIndices) {
    RunResult result;
    result.scenario = runs[static_cast<std::size_t>(r)].scenario.name;
    result.runId = runs[static_cast<std::size_t>(r)].id;
    result.backend = "talus";
    shard.results.results.push_back(result);
  }
  // Through the file format, as `merge` reads them.
  auto reread = ShardFromJson(ShardToJson(shard));
  EXPECT_TRUE(reread) << reread.GetError().message;
  return reread.Value();
}

std::string MergeError(const std::vector<ShardFile>& shards) {
  auto merged = MergeShards(shards);
  return merged ? std::string("(merged)") : merged.GetError().message;
}

class ShardPartition : public testing::Test {
 protected:
  void SetUp() override {
    runs = TwoScenarioRuns();
    ASSERT_EQ(runs.size(), 4u);
    first = MakeShard(runs, 0, 2);
    second = MakeShard(runs, 1, 2);
  }
  std::vector<harness::Run> runs;
  ShardFile first, second;
};

TEST_F(ShardPartition, AWholePartitionMergesInAnyOrder) {
  auto merged = MergeShards({second, first});
  ASSERT_TRUE(merged) << merged.GetError().message;
  ASSERT_EQ(merged.Value().results.size(), 4u);
  for (std::size_t r = 0; r < runs.size(); ++r) EXPECT_EQ(merged.Value().results[r].runId, runs[r].id);
  EXPECT_EQ(first.identity.build, BuildId());
  EXPECT_EQ(first.identity.scenarios, (std::vector<std::string>{"box_free_fall", "box_rest"}));
}

TEST_F(ShardPartition, MissingAndRepeatedShardsAreNamed) {
  EXPECT_EQ(MergeError({first}), "merge: shard 1/2 missing");
  EXPECT_EQ(MergeError({first, second, second}), "merge: shard 1/2 given twice");
}

TEST_F(ShardPartition, AnotherBuildIsRefusedNamingBoth) {
  second.identity.build = "0123456789ab GNU 12.2.0 Debug";
  EXPECT_EQ(MergeError({first, second}),
            std::string("merge: shard 1/2 has build \"0123456789ab GNU 12.2.0 Debug\" but "
                        "shard 0/2 has \"") +
                BuildId() + "\" (merge shards of one build)");
}

TEST_F(ShardPartition, OtherSettingsAreRefusedNamingTheSetting) {
  ShardFile steps = second;
  steps.identity.timeSteps = {0.01};
  EXPECT_NE(MergeError({first, steps})
                .find("has time steps \"0.01\" but shard 0/2 has "
                      "\"0.03333333333333333,0.016666666666666666\""),
            std::string::npos)
      << MergeError({first, steps});
  ShardFile iterations = second;
  iterations.identity.iterations = {10, 20};
  EXPECT_EQ(MergeError({first, iterations}),
            "merge: shard 1/2 has iterations \"10,20\" but shard 0/2 has \"10\"");
  ShardFile backends = second;
  backends.results.backends = {"bullet"};
  EXPECT_EQ(MergeError({first, backends}),
            "merge: shard 1/2 has backends \"bullet\" but shard 0/2 has \"talus\"");
  ShardFile timed = second;
  timed.results.deterministic = false;
  EXPECT_EQ(MergeError({first, timed}),
            "merge: shard 1/2 has --deterministic \"off\" but shard 0/2 has \"on\"");
  // The noise floor's settings go through the file and must agree.
  ShardFile copies = second;
  copies.identity.perturbCopies = 2;
  copies.identity.perturbation = 1e-9;
  auto reread = ShardFromJson(ShardToJson(copies));
  ASSERT_TRUE(reread) << reread.GetError().message;
  EXPECT_EQ(MergeError({first, reread.Value()}),
            "merge: shard 1/2 has perturbed copies (count, m) \"2, 1e-09\" but shard 0/2 has \"0, 0\"");
  ShardFile count = MakeShard(runs, 1, 3);
  EXPECT_EQ(MergeError({first, count}), "merge: shard 1/3 is one of 3 shards but shard 0/2 one of 2");
}

TEST_F(ShardPartition, AnotherScenarioSetIsRefusedNamingTheScenario) {
  std::vector<harness::Run> fewer(runs.begin(), runs.begin() + 2);  // box_free_fall only
  ShardFile other = MakeShard(fewer, 1, 2);
  EXPECT_EQ(MergeError({first, other}),
            "merge: shard 0/2 ran scenario \"box_rest\", which shard 1/2 did not");
}

// The same names with one number changed in one file (a friction edited on
// one machine) change the digest: refused, not merged.
TEST_F(ShardPartition, EditedScenarioContentsAreRefused) {
  std::vector<harness::Run> edited = runs;
  edited[3].scenario.bodies[0].friction += 0.125;
  const harness::ShardIdentity same = MakeShardIdentity(runs, {1.0 / 30.0, 1.0 / 60.0}, {10});
  EXPECT_EQ(same.runsDigest, first.identity.runsDigest);  // deterministic
  EXPECT_NE(MakeShardIdentity(edited, {1.0 / 30.0, 1.0 / 60.0}, {10}).runsDigest, same.runsDigest);
  ShardFile other = MakeShard(edited, 1, 2);
  const std::string message = MergeError({first, other});
  EXPECT_NE(message.find("ran the same scenario names with different contents"), std::string::npos)
      << message;
}

TEST_F(ShardPartition, OldAndForgedShardFilesAreRefusedBeforeAnyAllocation) {
  std::string text = ShardToJson(first);
  std::string old = text;
  old.replace(old.find("\"version\": 3"), 12, "\"version\": 1");
  auto refused = ShardFromJson(old);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.GetError().message.find("version 1, expected 3 (written by an older talus-testbed"),
            std::string::npos)
      << refused.GetError().message;
  std::string forged = text;
  forged.replace(forged.find("\"count\": 2"), 10, "\"count\": 2000000000");
  auto huge = ShardFromJson(forged);
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.GetError().message.find("count 2000000000"), std::string::npos) << huge.GetError().message;
}

}  // namespace shard_identity_test
}  // namespace talus::harness
