// A scenario's "backends" and "measure" lists in the runner: each run goes
// to the backends asked for that its scenario lists (in the asked order), an
// unknown listed name is refused with the file and pointer before anything
// runs, a run left with nothing to run is reported, the optional metrics
// exist only when measured, and the output stays byte-identical whatever
// the thread count and sharding.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/sweep/sweep.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace scenario_backends_test {

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

const BackendRegistry& Registry() { return reference::AllBackends(); }

// A falling sphere (a closed system: no static body), 20 steps, with the
// given extra top-level fields (e.g. "\"backends\": [\"talus\"],").
std::vector<ScenarioRun> Falling(const std::string& name, const std::string& extra) {
  const std::string text = R"({"name": ")" + name + R"(", )" + extra +
                           R"( "world": {"timeStep": 0.01, "duration": {"steps": 20}},
      "bodies": [{"name": "ball", "shape": {"kind": "sphere", "radius": 0.5}, "motion": "dynamic",
                  "position": [0, 2, 0], "mass": 1}]})";
  auto runs = ParseScenarioText(text, name + ".json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value() : std::vector<ScenarioRun>{};
}

std::vector<std::string> BackendsOf(const std::vector<RunResult>& results, const std::string& runId) {
  std::vector<std::string> names;
  for (const RunResult& r : results) {
    if (r.runId == runId) names.push_back(r.backend);
  }
  return names;
}

std::vector<std::string> MetricNames(const RunResult& result) {
  std::vector<std::string> names;
  for (const MetricResult& m : result.metrics) names.push_back(m.name);
  return names;
}

// Three scenarios: one listing two backends (in the opposite order to the
// command line), one listing none, one whose only backend is not asked for.
std::vector<ScenarioRun> Mixed() {
  std::vector<ScenarioRun> runs = Falling("listed", R"("backends": ["bullet", "talus"],)");
  for (ScenarioRun& run : Falling("unlisted", "")) runs.push_back(run);
  for (ScenarioRun& run : Falling("elsewhere", R"("backends": ["talus-split"],)")) runs.push_back(run);
  return runs;
}

TEST(ScenarioBackends, EachRunGoesToTheIntersectionInTheAskedOrder) {
  RunnerOptions options;
  options.backends = {"talus", "ode-step", "bullet"};
  std::vector<std::string> notices;
  options.notice = [&](const std::string& line) { notices.push_back(line); };
  auto results = RunAll(Registry(), Mixed(), options);
  ASSERT_TRUE(results) << results.GetError().message;
  EXPECT_EQ(BackendsOf(results.Value(), "listed"), (std::vector<std::string>{"talus", "bullet"}));
  EXPECT_EQ(BackendsOf(results.Value(), "unlisted"), options.backends);
  EXPECT_TRUE(BackendsOf(results.Value(), "elsewhere").empty());
  EXPECT_EQ(results.Value().size(), 5u);
  for (const RunResult& r : results.Value()) EXPECT_TRUE(r.error.empty()) << r.runId << " " << r.error;
}

TEST(ScenarioBackends, RunWithNothingInCommonIsReportedNotDropped) {
  RunnerOptions options;
  options.backends = {"talus", "ode-step", "bullet"};
  std::vector<std::string> notices;
  options.notice = [&](const std::string& line) { notices.push_back(line); };
  ASSERT_TRUE(RunAll(Registry(), Mixed(), options));
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_NE(notices[0].find("elsewhere (elsewhere.json): not run: its backends (talus-split) and those asked "
                            "for (talus, ode-step, bullet) have none in common"),
            std::string::npos)
      << notices[0];
  // Asking for the listed backend runs it, with no notice.
  notices.clear();
  options.backends = {"talus-split"};
  auto results = RunAll(Registry(), Mixed(), options);
  ASSERT_TRUE(results);
  EXPECT_EQ(BackendsOf(results.Value(), "elsewhere"), options.backends);
  ASSERT_EQ(notices.size(), 1u);  // now "listed" has nothing in common
  EXPECT_EQ(notices[0].rfind("listed (listed.json): not run", 0), 0u) << notices[0];
}

TEST(ScenarioBackends, UnknownListedBackendIsRefusedWithFileAndPointerBeforeRunning) {
  std::vector<ScenarioRun> runs = Falling("good", "");
  for (ScenarioRun& run : Falling("bad", R"("backends": ["talus", "havok"],)")) runs.push_back(run);
  RunnerOptions options;
  options.backends = {"talus"};
  int progressCalls = 0;
  options.progress = [&](const std::string&) { ++progressCalls; };
  auto results = RunAll(Registry(), runs, options);
  ASSERT_FALSE(results);
  EXPECT_NE(results.GetError().message.find("bad.json: /backends/1: unknown backend \"havok\" (known: "),
            std::string::npos)
      << results.GetError().message;
  EXPECT_EQ(progressCalls, 0);  // refused before the first job
  // The name is refused even when the command line does not ask for it.
  options.backends = {"bullet"};
  EXPECT_FALSE(RunAll(Registry(), runs, options));
}

TEST(ScenarioBackends, MeasureListDecidesTheOptionalMetrics) {
  RunnerOptions options;
  const RunResult none = RunOne(Registry(), Falling("none", "")[0], "talus", options);
  ASSERT_TRUE(none.error.empty()) << none.error;
  EXPECT_TRUE(none.metrics.empty()) << MetricNames(none).size() << " metrics without a measure list";

  const RunResult energy =
      RunOne(Registry(), Falling("energy", R"("measure": ["energy"],)")[0], "talus", options);
  EXPECT_EQ(MetricNames(energy), (std::vector<std::string>{"energy.drift", "energy.drift_relative"}));

  const RunResult all = RunOne(
      Registry(),
      Falling("all",
              R"("measure": ["position", "velocity", "energy", "momentum", "contacts", "penetration"],)")[0],
      "talus", options);
  EXPECT_EQ(MetricNames(all),
            (std::vector<std::string>{"energy.drift", "energy.drift_relative", "momentum.linear_drift",
                                      "momentum.angular_drift", "penetration.max", "contacts.final"}));
  // A free fall in the air: no contact, and symplectic Euler keeps the
  // momentum law M g t to round-off (the 1e-9 N s of runner_test).
  EXPECT_EQ(all.metrics[5].measured, 0.0);
  EXPECT_LT(all.metrics[2].measured, 1e-9);
}

TEST(ScenarioBackends, OutputIsByteIdenticalWhateverTheThreadCountAndSharding) {
  const std::vector<ScenarioRun> runs = Mixed();
  RunnerOptions options;
  options.backends = {"talus", "ode-step", "bullet"};
  options.deterministic = true;
  options.jobs = 1;
  auto serial = RunAll(Registry(), runs, options);
  ASSERT_TRUE(serial);
  const std::string expected = ResultsToJson({options.backends, true, serial.Value()});
  options.jobs = 3;
  auto threaded = RunAll(Registry(), runs, options);
  ASSERT_TRUE(threaded);
  EXPECT_EQ(ResultsToJson({options.backends, true, threaded.Value()}), expected);

  // Two shards, each run's result count recorded, merge back to the same.
  std::vector<ShardFile> shards;
  for (int index : {1, 0}) {
    ShardFile shard;
    shard.shard = {index, 2};
    shard.runCount = static_cast<int>(runs.size());
    shard.runIndices = ShardRuns(shard.runCount, shard.shard);
    std::vector<ScenarioRun> part;
    for (int r : shard.runIndices) {
      part.push_back(runs[static_cast<std::size_t>(r)]);
      auto chosen = BackendsForRun(Registry(), part.back(), options.backends);
      ASSERT_TRUE(chosen);
      shard.resultCounts.push_back(static_cast<int>(chosen.Value().size()));
    }
    auto results = RunAll(Registry(), part, options);
    ASSERT_TRUE(results);
    shard.results = {options.backends, true, results.Value()};
    auto reread = ShardFromJson(ShardToJson(shard));
    ASSERT_TRUE(reread) << reread.GetError().message;
    shards.push_back(reread.Value());
  }
  auto merged = MergeShards(shards);
  ASSERT_TRUE(merged) << merged.GetError().message;
  EXPECT_EQ(ResultsToJson(merged.Value()), expected);
  // Counts that do not add up to the shard's results are refused.
  shards[1].resultCounts[0] += 1;
  EXPECT_FALSE(MergeShards(shards));
}

}  // namespace scenario_backends_test
}  // namespace talus::harness
