// The sweep's noise floor (harness sweep/perturbed_copies.h and the range
// in sweep.h's comparisons): overlapping ranges of best and worst copy are
// a tie; the range that applies is that of the point the budget buys. A
// perturbed copy really moves every dynamic body, by at most the amount,
// and is judged against the truth of its own start; copies are
// bit-identical whatever the thread count; 0 copies is today's sweep
// exactly; files without spreads load as spread 0.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/command_outcome.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/sweep/perturbed_copies.h"
#include "talus/harness/sweep/sweep.h"
#include "talus/reference/all_backends.h"
#include "testbed/one_metric_run.h"

namespace talus::harness {
namespace noise_floor_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

FamilyPoints Family(std::string name, std::vector<CostErrorPoint> points) {
  return {std::move(name), {}, std::move(points)};
}

// ---- The copies' range in the comparisons (hand-made fronts) ----

TEST(NoiseFloor, TheRangeOfThePointTheBudgetBuysApplies) {
  // Talus's cheap point is noisy ([1.5, 2.5] over its copies), its dear one
  // is not; at the cheap budget it overlaps Bullet's 1.8 (a tie), at the
  // dear budget 1.0 against 0.9 is worse. A floor taken from the noisiest
  // point would hide that loss.
  const FamilyPair pair = CompareFamilyPair(
      Family("Talus", {{.cost = 1.0, .error = 2.0, .spread = 1.0, .best = 1.5, .worst = 2.5}, {4.0, 1.0}}),
      Family("Bullet", {{1.0, 1.8}, {4.0, 0.9}}));
  EXPECT_EQ(pair.outcome, PairOutcome::kSecondBetter);
  EXPECT_EQ(pair.firstWins, 0);
  EXPECT_EQ(pair.secondWins, 1);
  EXPECT_DOUBLE_EQ(pair.budget, 4.0);
}

TEST(NoiseFloor, WithoutCopiesTheComparisonIsExact) {
  // Round-off-sized margins decide when nothing measured a range.
  const FamilyPair pair =
      CompareFamilyPair(Family("Talus", {{1.0, 8e-10}}), Family("Bullet", {{1.0, 2e-11}}));
  EXPECT_EQ(pair.outcome, PairOutcome::kSecondBetter);
  const CostErrorPoint a{1.0, 1.0};
  const CostErrorPoint b{1.0, std::nextafter(1.0, 2.0)};
  EXPECT_EQ(CompareAtBudget(&a, &b), BudgetOutcome::kFirst);
}

TEST(NoiseFloor, CompareFrontsGivesNoWinToOverlappingRanges) {
  // Backend 0 is better by 0.05 at both budgets, but its copies range 0.1.
  const std::vector<CostErrorPoint> a{
      {.cost = 1.0, .error = 0.95, .spread = 0.1, .best = 0.9, .worst = 1.0},
      {.cost = 2.0, .error = 0.5, .spread = 0.1, .best = 0.45, .worst = 0.55}};
  const std::vector<CostErrorPoint> b{{1.0, 1.00}, {2.0, 0.55}};
  const FrontComparison tied = CompareFronts({a, b});
  EXPECT_EQ(tied.winner, -1);
  EXPECT_EQ(tied.wins, (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(tied.spreadAtMatched[0], 0.1);

  const std::vector<CostErrorPoint> quiet{
      {.cost = 1.0, .error = 0.95, .spread = 0.01, .best = 0.94, .worst = 0.95},
      {.cost = 2.0, .error = 0.5, .spread = 0.01, .best = 0.5, .worst = 0.51}};
  const FrontComparison won = CompareFronts({quiet, b});
  EXPECT_EQ(won.winner, 0);
  EXPECT_EQ(won.wins, (std::vector<int>{2, 0}));
}

TEST(ErrorSpread, IsMaxMinusMinAndInfiniteWhenOnlySomeRunsWereMeasured) {
  EXPECT_DOUBLE_EQ(ErrorSpread({0.5, 0.7, 0.6}), 0.7 - 0.5);
  EXPECT_EQ(ErrorSpread({0.5}), 0.0);
  EXPECT_EQ(ErrorSpread({kInf, kInf}), 0.0);
  EXPECT_EQ(ErrorSpread({0.5, kInf}), kInf);
  EXPECT_EQ(ErrorSpread({0.5, std::nan("")}), kInf);  // a failed copy
}

// ---- The copies ----

std::vector<harness::Run> SlideRuns() {
  auto loaded = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/sliding/box_slide.json"});
  EXPECT_TRUE(loaded) << loaded.GetError().message;
  // One instance at one short stepping keeps the runs cheap.
  std::vector<harness::Run> one{loaded.Value().front()};
  auto expanded = ExpandStepping(one, {1.0 / 30.0}, {5});
  EXPECT_TRUE(expanded);
  return expanded.Value();
}

TEST(PerturbedCopies, EachCopyMovesEveryDynamicBodyByAtMostTheAmount) {
  const std::vector<harness::Run> runs = SlideRuns();
  ASSERT_EQ(runs.size(), 1u);
  constexpr double kAmount = 1e-9;
  auto copies = WithPerturbedCopies(runs, 2, kAmount);
  ASSERT_TRUE(copies) << copies.GetError().message;
  ASSERT_EQ(copies.Value().size(), 3u);
  const Scenario& original = runs[0].scenario;
  EXPECT_EQ(ScenarioToJson(copies.Value()[0].scenario), ScenarioToJson(original));
  for (int k = 1; k <= 2; ++k) {
    const Scenario& copy = copies.Value()[static_cast<std::size_t>(k)].scenario;
    ASSERT_EQ(copy.bodies.size(), original.bodies.size());
    for (std::size_t b = 0; b < copy.bodies.size(); ++b) {
      int moved = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const double offset = copy.bodies[b].position[axis] - original.bodies[b].position[axis];
        // The offset itself is <= 1e-9; adding it to a coordinate of size
        // <= 1 m rounds by at most 2^-53 m more.
        EXPECT_LE(std::abs(offset), kAmount + 1e-15) << "body " << b << " axis " << axis;
        if (offset != 0.0) ++moved;
      }
      if (original.bodies[b].motion == Motion::Dynamic) {
        EXPECT_EQ(moved, 3) << "copy " << k << ": dynamic body " << b << " must move on every axis";
      } else {
        EXPECT_EQ(moved, 0) << "copy " << k << ": static body " << b << " must stay put";
      }
    }
  }
  // The two copies draw from different seeds.
  EXPECT_NE(copies.Value()[1].scenario.bodies[1].position[0],
            copies.Value()[2].scenario.bodies[1].position[0]);
}

TEST(PerturbedCopies, NoCopiesIsTodaysSweepExactly) {
  const std::vector<harness::Run> runs = SlideRuns();
  auto same = WithPerturbedCopies(runs, 0, 1e-9);
  ASSERT_TRUE(same);
  ASSERT_EQ(same.Value().size(), runs.size());
  EXPECT_EQ(ScenarioToJson(same.Value()[0].scenario), ScenarioToJson(runs[0].scenario));
  EXPECT_EQ(same.Value()[0].id, runs[0].id);

  RunnerOptions options;
  options.backends = {"talus"};
  options.deterministic = true;
  auto results = RunAll(reference::AllBackends(), runs, options);
  ASSERT_TRUE(results);
  auto folded = FoldPerturbedCopies(results.Value(), {1}, 0, 1e-9);
  ASSERT_TRUE(folded);
  const ResultsFile plain{options.backends, true, results.Value()};
  const ResultsFile none{options.backends, true, folded.Value()};
  const std::string text = ResultsToJson(none);
  EXPECT_EQ(text, ResultsToJson(plain));
  EXPECT_EQ(text.find("\"perturbed\""), std::string::npos);
}

TEST(PerturbedCopies, AreBitIdenticalWithOneThreadAndTwo) {
  const std::vector<harness::Run> runs = SlideRuns();
  auto copies = WithPerturbedCopies(runs, 2, 1e-9);
  ASSERT_TRUE(copies);
  std::string text[2];
  for (int jobs : {1, 2}) {
    RunnerOptions options;
    options.backends = {"talus", "ode-step"};
    options.jobs = jobs;
    options.deterministic = true;
    auto results = RunAll(reference::AllBackends(), copies.Value(), options);
    ASSERT_TRUE(results);
    ASSERT_EQ(results.Value().size(), 6u);
    auto folded = FoldPerturbedCopies(results.Value(), {2}, 2, 1e-9);
    ASSERT_TRUE(folded) << folded.GetError().message;
    ASSERT_EQ(folded.Value().size(), 2u);
    for (const RunResult& r : folded.Value()) {
      EXPECT_EQ(r.perturbed.copies, 2);
      EXPECT_EQ(r.perturbed.runSeconds.size(), 3u);
      // The copies change the outcome, not only the input: box_slide's
      // stop distance at h = 1/30 s moves by about 2e-7 tolerances (talus)
      // and 7e-8 (ode-step) under 1e-9 m, measured.
      EXPECT_GT(r.perturbed.errorSpread, 0.0) << r.backend;
      EXPECT_EQ(r.runId, runs[0].id);  // the unperturbed run's result is kept
    }
    text[jobs - 1] = ResultsToJson({options.backends, true, folded.Value()});
  }
  EXPECT_EQ(text[0], text[1]);
}

TEST(PerturbedCopies, EachCopyIsJudgedAgainstTheTruthOfItsOwnStart) {
  // box_free_fall's truth has a 1e-9 m tolerance; judged against the
  // unperturbed start, the copies' 1e-9 m offsets alone were an error of
  // 0.67 at every point, for every engine. Against their own starts only
  // round-off over 60 steps of a 10 m fall remains (about 1e-14 m, the
  // file's reason), so the spread is far below 0.01.
  auto loaded = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/tumbling/box_free_fall.json"});
  ASSERT_TRUE(loaded) << loaded.GetError().message;
  auto copies = WithPerturbedCopies(loaded.Value(), 2, 1e-9);
  ASSERT_TRUE(copies) << copies.GetError().message;
  const auto& fall = std::get<FreeFallTruth>(copies.Value()[1].scenario.truths[0].kind);
  EXPECT_EQ(fall.y0 - 10.0, copies.Value()[1].scenario.bodies[0].position.y() - 10.0);
  EXPECT_NE(fall.y0, 10.0);
  RunnerOptions options;
  options.backends = {"talus"};
  options.deterministic = true;
  auto results = RunAll(reference::AllBackends(), copies.Value(), options);
  ASSERT_TRUE(results);
  auto folded = FoldPerturbedCopies(results.Value(), {1}, 2, 1e-9);
  ASSERT_TRUE(folded) << folded.GetError().message;
  const PerturbedRuns& p = folded.Value().at(0).perturbed;
  EXPECT_LT(p.errorSpread, 0.01);
  for (double error : p.errors) EXPECT_LT(error, 0.01);
}

TEST(PerturbedCopies, ResultsThatDoNotMatchTheCountsAreRefused) {
  std::vector<RunResult> results(5);
  for (RunResult& r : results) r.backend = "talus";
  auto short_ = FoldPerturbedCopies(results, {2}, 2, 1e-9);  // needs 6
  ASSERT_FALSE(short_);
  EXPECT_NE(short_.GetError().message.find("fewer results"), std::string::npos);
  results.resize(6);
  results[3].backend = "bullet";  // copy 1 of backend 1 ran elsewhere
  auto mixed = FoldPerturbedCopies(results, {2}, 2, 1e-9);
  ASSERT_FALSE(mixed);
  EXPECT_NE(mixed.GetError().message.find("copy 1 ran on"), std::string::npos) << mixed.GetError().message;
}

// ---- The file format ----

RunResult PointResult(double error, double seconds) {
  RunResult r = sweep_fixture::OneMetricRun("talus", "0.01", 0.01, seconds, error);
  r.settings = {{"engine", "Talus (double)"}};
  return r;
}

TEST(PerturbedCopies, SpreadsSurviveTheResultsFileAndOldFilesLoadWithSpreadZero) {
  RunResult withCopies = PointResult(0.5, 1.0);
  withCopies.perturbed = {2, 1e-9, kInf, {1.0, 1.1, 0.9}, {0.5, kInf, 0.4}};  // infinite: written as null
  RunResult old = PointResult(0.4, 1.0);
  old.backend = "bullet";
  old.settings = {{"engine", "Bullet 324"}};
  const std::string text = ResultsToJson({{"talus", "bullet"}, false, {withCopies, old}});
  auto back = ResultsFromJson(text);
  ASSERT_TRUE(back) << back.GetError().message;
  EXPECT_EQ(back.Value().results[0].perturbed.errorSpread, kInf);
  EXPECT_EQ(back.Value().results[0].perturbed.runSeconds, (std::vector<double>{1.0, 1.1, 0.9}));
  EXPECT_EQ(back.Value().results[0].perturbed.errors, (std::vector<double>{0.5, kInf, 0.4}));
  EXPECT_EQ(back.Value().results[0].wallSeconds, 1.0);
  EXPECT_EQ(back.Value().results[1].perturbed.copies, 0);
  EXPECT_EQ(back.Value().results[1].perturbed.errorSpread, 0.0);

  // With the copies' errors, Talus's failed copy makes it worse than Bullet.
  const std::vector<SweepGroup> withErrors = AnalyseSweep(back.Value(), {});
  ASSERT_EQ(withErrors.size(), 1u);
  ASSERT_EQ(withErrors[0].families.pairs.size(), 1u);
  EXPECT_EQ(withErrors[0].families.pairs[0].outcome, PairOutcome::kSecondBetter);
  EXPECT_EQ(withErrors[0].families.pairs[0].firstWorst, kInf);

  // A file written before the noise floor (no "perturbed" anywhere, no
  // total wall time) is compared exactly: Talus 0.5 against Bullet 0.4 is
  // worse; its cost is the mean step times the steps.
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(text);
  json["results"][0].erase("perturbed");
  json["results"][0].erase("wallSeconds");
  auto older = ResultsFromJson(json.dump());
  ASSERT_TRUE(older) << older.GetError().message;
  EXPECT_EQ(older.Value().results[0].wallSeconds, 0.1 * 10);
  EXPECT_TRUE(std::isnan(older.Value().results[0].wallSecondsLongestStep));
  const std::vector<SweepGroup> groups = AnalyseSweep(older.Value(), {});
  ASSERT_EQ(groups.size(), 1u);
  ASSERT_EQ(groups[0].families.pairs.size(), 1u);
  EXPECT_EQ(groups[0].families.pairs[0].outcome, PairOutcome::kSecondBetter);
  EXPECT_EQ(groups[0].families.pairs[0].firstWorst, 0.5);

  // Every version-2 writer keeps the copies' errors: a block with the
  // spread but without them is refused at its place, not widened to a guess.
  json = nlohmann::ordered_json::parse(text);
  json["results"][0]["perturbed"].erase("errors");
  auto spreadOnly = ResultsFromJson(json.dump());
  ASSERT_FALSE(spreadOnly);
  EXPECT_NE(spreadOnly.GetError().message.find("/results/0/perturbed"), std::string::npos)
      << spreadOnly.GetError().message;

  // A malformed block is refused at its place.
  json = nlohmann::ordered_json::parse(text);
  json["results"][0]["perturbed"]["runSeconds"] = {1.0};
  auto bad = ResultsFromJson(json.dump());
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.GetError().message.find("/results/0/perturbed"), std::string::npos) << bad.GetError().message;
}

// ---- The command line ----

#ifdef TALUS_TESTBED_BINARY
talus::testing_support::CommandOutcome Sweep(const std::string& arguments) {
  return talus::testing_support::RunCommand(std::string(TALUS_TESTBED_BINARY) + " sweep -q " + arguments);
}

TEST(PerturbedCopies, BadOptionValuesAreRefusedNamingTheOption) {
  for (const char* arguments : {"--perturb-copies -1", "--perturb-copies 17", "--perturb nan", "--perturb 0",
                                "--perturb -1e-9", "--perturb 1"}) {
    const auto outcome = Sweep(std::string(arguments) + " -o /nonexistent/never-written");
    const std::string option = std::string(arguments).substr(0, std::string(arguments).find(' '));
    EXPECT_EQ(outcome.code, 2) << arguments << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("sweep: " + option + " "), std::string::npos)
        << arguments << ": " << outcome.output;
  }
}
#endif

}  // namespace noise_floor_test
}  // namespace talus::harness
