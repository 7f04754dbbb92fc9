// The run-time-against-error analysis and sharding (harness sweep.h): the
// error scalar, Pareto fronts and the equal-cost comparison on hand-made
// points; the shard partition covers every job exactly once, and merging
// the shards of a real sweep gives the unsharded results file byte for
// byte (deterministic mode).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/sweep/sweep.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace sweep_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

MetricResult Metric(double error, double truth, double absolute, double relative, bool checked) {
  MetricResult metric = MakeMetric("m", "m");
  metric.measured = truth + error;
  metric.error = error;
  metric.truth = truth;
  metric.tolerance = {absolute, relative};
  metric.checked = checked;
  return metric;
}

TEST(RunErrorScalar, IsTheLargestErrorOverItsToleranceScale) {
  RunResult result;
  // Scales: 0.01 + 0.1 * 2 = 0.21 and 0.5 (an ungated metric counts too);
  // metrics without a tolerance (drift, contacts) do not count.
  result.metrics = {Metric(-0.042, 2.0, 0.01, 0.1, true), Metric(0.25, 10.0, 0.5, 0.0, false),
                    Metric(100.0, 1.0, 0.0, 0.0, false)};
  EXPECT_NEAR(RunErrorScalar(result), 0.5, 1e-15);                        // 0.25 / 0.5 > 0.042 / 0.21 = 0.2
  result.metrics[0].measured = std::numeric_limits<double>::quiet_NaN();  // not measured
  EXPECT_EQ(RunErrorScalar(result), kInf);
}

TEST(RunErrorScalar, IsTheDistanceToTheContinuousTruthNotToTheIntegratorsAnswer) {
  // A run exactly on symplectic Euler's sequence (error 0 against the
  // integrator-exact answer) that lags the continuous truth by 0.1: the
  // sweep charges it the 0.1, 2 tolerances, so a finer step can earn less.
  RunResult result;
  MetricResult metric = Metric(0.0, 1.0, 0.05, 0.0, true);
  metric.truthIntegrator = 0.9;
  metric.measured = 0.9;
  result.metrics = {metric};
  EXPECT_NEAR(RunErrorScalar(result), 2.0, 1e-12);
  // An engine exact in continuous time is not charged for leaving the sequence.
  result.metrics[0].measured = 1.0;
  result.metrics[0].error = 0.1;
  EXPECT_NEAR(RunErrorScalar(result), 0.0, 1e-12);
}

TEST(RunErrorScalar, IsNaNWithoutAToleranceOrWhenTheRunFailed) {
  RunResult result;
  result.metrics = {Metric(1.0, 1.0, 0.0, 0.0, false)};
  EXPECT_TRUE(std::isnan(RunErrorScalar(result)));
  result.metrics[0].tolerance.absolute = 0.1;
  EXPECT_NEAR(RunErrorScalar(result), 10.0, 1e-12);
  result.error = "refused";
  EXPECT_TRUE(std::isnan(RunErrorScalar(result)));
}

TEST(ParetoFront, KeepsExactlyTheNonDominatedPointsByIncreasingCost) {
  // (cost, error): 1 dominated by 0; 3 by 2; 5 (equal to 4) is a duplicate;
  // 6 has infinite error.
  const std::vector<CostErrorPoint> points{{1.0, 5.0}, {2.0, 6.0}, {3.0, 1.0},   {3.5, 1.0},
                                           {0.5, 9.0}, {0.5, 9.0}, {10.0, kInf}, {8.0, 0.1}};
  EXPECT_EQ(ParetoFront(points), (std::vector<int>{4, 0, 2, 7}));
  EXPECT_TRUE(ParetoFront({{1.0, kInf}}).empty());
  EXPECT_TRUE(ParetoFront({}).empty());
}

TEST(FrontErrorAt, IsTheBestErrorWithinTheBudget) {
  const std::vector<CostErrorPoint> front{{1.0, 5.0}, {3.0, 1.0}, {8.0, 0.1}};
  EXPECT_EQ(FrontErrorAt(front, 0.5), kInf);
  EXPECT_EQ(FrontErrorAt(front, 1.0), 5.0);
  EXPECT_EQ(FrontErrorAt(front, 7.9), 1.0);
  EXPECT_EQ(FrontErrorAt(front, 100.0), 0.1);
}

TEST(CompareFronts, TheWinnerHasTheLowerErrorAtMostMatchedBudgets) {
  // A is cheap and coarse; B starts at cost 2 (the matched cost) and is
  // more accurate from there except at budget 4, where A's 0.2 beats B's 0.5.
  const std::vector<CostErrorPoint> a{{0.5, 3.0}, {4.0, 0.2}};
  const std::vector<CostErrorPoint> b{{2.0, 0.5}, {5.0, 0.01}};
  const FrontComparison c = CompareFronts({a, b});
  EXPECT_EQ(c.matchedCost, 2.0);
  EXPECT_EQ(c.budgets, 3);  // 2, 4, 5
  EXPECT_EQ(c.wins, (std::vector<int>{1, 2}));
  EXPECT_EQ(c.winner, 1);
  EXPECT_EQ(c.errorAtMatched, (std::vector<double>{3.0, 0.5}));
  // Equal fronts tie everywhere: no winner.
  EXPECT_EQ(CompareFronts({a, a}).winner, -1);
  EXPECT_EQ(CompareFronts({a, {}}).winner, -1);
}

TEST(ParseShard, AcceptsIOverNAndNamesBadText) {
  auto shard = ParseShard("2/5");
  ASSERT_TRUE(shard);
  EXPECT_EQ(shard.Value().index, 2);
  EXPECT_EQ(shard.Value().count, 5);
  for (const char* bad : {"5/5", "-1/3", "1", "a/b", "1/0", "1/2x", ""}) {
    auto parsed = ParseShard(bad);
    ASSERT_FALSE(parsed) << bad;
    EXPECT_NE(parsed.GetError().message.find("shard"), std::string::npos);
  }
}

TEST(ParseShard, AnIndexOutOfRangeSaysShardsNumberFromZero) {
  // "--shard 2/2" is a natural first guess at the second of two shards
  // (issue 39): the refusal says how they are numbered.
  auto parsed = ParseShard("2/2");
  ASSERT_FALSE(parsed);
  EXPECT_NE(
      parsed.GetError().message.find("shard index 2 out of range for 2 shards (shards are numbered 0 to 1)"),
      std::string::npos)
      << parsed.GetError().message;
  auto negative = ParseShard("-1/3");
  ASSERT_FALSE(negative);
  EXPECT_NE(negative.GetError().message.find(
                "shard index -1 out of range for 3 shards (shards are numbered 0 to 2)"),
            std::string::npos)
      << negative.GetError().message;
}

TEST(ShardRuns, ThePartitionCoversEveryRunExactlyOnce) {
  for (int runs : {0, 1, 7, 48, 101}) {
    for (int count : {1, 2, 3, 8, 200}) {
      std::multiset<int> seen;
      for (int index = 0; index < count; ++index) {
        for (int r : ShardRuns(runs, {index, count})) seen.insert(r);
      }
      ASSERT_EQ(static_cast<int>(seen.size()), runs);
      for (int r = 0; r < runs; ++r) EXPECT_EQ(seen.count(r), 1u) << runs << " runs, " << count << " shards";
    }
  }
}

const BackendRegistry& Registry() { return reference::AllBackends(); }

TEST(MergeShards, MergedShardsAreByteIdenticalToTheUnshardedSweep) {
  auto loaded = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/tumbling/box_free_fall.json",
                               std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json"});
  ASSERT_TRUE(loaded) << loaded.GetError().message;
  auto expanded = ExpandStepping(loaded.Value(), {1.0 / 30.0, 1.0 / 60.0}, {5, 10});
  ASSERT_TRUE(expanded);
  const std::vector<harness::Run>& runs = expanded.Value();
  ASSERT_EQ(runs.size(), 8u);
  RunnerOptions options;
  options.backends = {"talus", "ode-step"};
  options.jobs = 2;
  options.deterministic = true;
  auto whole = RunAll(Registry(), runs, options);
  ASSERT_TRUE(whole);
  ResultsFile unsharded{options.backends, true, whole.Value()};

  constexpr int kShards = 3;
  std::vector<ShardFile> shards;
  for (int index = kShards - 1; index >= 0; --index) {  // any order
    ShardFile shard;
    shard.shard = {index, kShards};
    shard.runCount = static_cast<int>(runs.size());
    shard.runIndices = ShardRuns(shard.runCount, shard.shard);
    std::vector<harness::Run> part;
    for (int r : shard.runIndices) part.push_back(runs[static_cast<std::size_t>(r)]);
    auto results = RunAll(Registry(), part, options);
    ASSERT_TRUE(results);
    shard.results = {options.backends, true, results.Value()};
    auto reread = ShardFromJson(ShardToJson(shard));  // through the file format
    ASSERT_TRUE(reread) << reread.GetError().message;
    shards.push_back(reread.Value());
  }
  auto merged = MergeShards(shards);
  ASSERT_TRUE(merged) << merged.GetError().message;
  EXPECT_EQ(ResultsToJson(merged.Value()), ResultsToJson(unsharded));

  // An incomplete or repeated partition is refused with the shard named.
  auto missing = MergeShards({shards[0], shards[1]});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("0/3 missing"), std::string::npos) << missing.GetError().message;
  auto twice = MergeShards({shards[0], shards[0], shards[1], shards[2]});
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.GetError().message.find("given twice"), std::string::npos);
}

TEST(AnalyseSweep, GroupsStepsIntoCurvesPerBackendAndIterations) {
  // Hand-made results: one instance, backend "a" at two iteration counts,
  // "s" ignoring iterations (its second count is dropped).
  ResultsFile file;
  file.backends = {"a", "s"};
  const auto add = [&](const std::string& backend, int iterations, double h, double seconds, double error) {
    RunResult r;
    r.scenario = "drop";
    r.runId = "drop[h=..]";
    r.backend = backend;
    r.sweepValues = {{"mu", "0.5"}, {"h", "x"}, {"iterations", std::to_string(iterations)}};
    r.timeStep = h;
    r.iterations = iterations;
    r.steps = 10;
    r.wallSecondsPerStepMedian = seconds / 10.0;
    r.wallSeconds = seconds;
    r.metrics = {Metric(error, 1.0, 1.0, 0.0, true)};
    file.results.push_back(r);
  };
  add("a", 5, 0.1, 1.0, 2.0);
  add("s", 5, 0.1, 0.5, 4.0);
  add("a", 10, 0.1, 2.0, 3.0);  // dominated by (1, 2)
  add("s", 10, 0.1, 0.5, 4.0);
  add("a", 5, 0.05, 4.0, 0.5);
  add("s", 5, 0.05, 1.0, 1.0);
  const std::vector<SweepGroup> groups = AnalyseSweep(file, {"s"});
  ASSERT_EQ(groups.size(), 1u);
  const SweepGroup& g = groups[0];
  EXPECT_EQ(g.id, "drop[mu=0.5]");
  ASSERT_EQ(g.curves.size(), 3u);
  EXPECT_EQ(g.curves[0].backend, "a");
  EXPECT_EQ(g.curves[0].onFront, (std::vector<bool>{true, true}));
  EXPECT_EQ(g.curves[1].onFront, (std::vector<bool>{false}));
  EXPECT_EQ(g.curves[2].backend, "s");
  EXPECT_EQ(g.curves[2].points.size(), 2u);
  // Matched cost 1 s (a's cheapest); budgets 1 and 4: s wins at 1 (1 < 2),
  // a at 4 (0.5 < 1): a tie, so no winner.
  EXPECT_EQ(g.comparison.matchedCost, 1.0);
  EXPECT_EQ(g.comparison.wins, (std::vector<int>{1, 1}));
  EXPECT_EQ(g.comparison.winner, -1);
  EXPECT_NE(SweepMarkdown(groups).find("| drop[mu=0.5] | none (tie) |"), std::string::npos);
}

}  // namespace sweep_test
}  // namespace talus::harness
