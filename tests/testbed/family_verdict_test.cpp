// The family verdict of the sweep analysis (sweep.h CompareAtBudget,
// CompareFamilyPair, CompareFamilies and their use in AnalyseSweep): every
// engine family against every other, better, tie or worse, at the cost of
// every point of either. Every case is hand-made so the answer can be read
// off the points; the cases of issue 24 go through a results file written
// and read back, the path `talus-testbed report --sweep` takes.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/sweep.h"
#include "testbed/one_metric_run.h"

namespace talus::harness {
namespace family_verdict_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

FamilyPoints Family(std::string name, std::vector<CostErrorPoint> points) {
  return {std::move(name), {}, std::move(points)};
}

// A point with perturbed copies: error of the unperturbed run, then the
// best and worst over the run and its copies.
CostErrorPoint Copies(double cost, double error, double best, double worst) {
  return {.cost = cost, .error = error, .spread = worst - best, .best = best, .worst = worst};
}

// A results file of hand-made runs of one scenario instance (one metric,
// tolerance 1 absolute, so each run's error scalar is its error).
struct FileBuilder {
  ResultsFile file;
  RunResult& Add(const std::string& backend, const std::string& engine, double h, double seconds,
                 double error) {
    if (std::find(file.backends.begin(), file.backends.end(), backend) == file.backends.end())
      file.backends.push_back(backend);
    RunResult r = sweep_fixture::OneMetricRun(backend, std::to_string(h), h, seconds, error);
    if (!engine.empty()) r.settings = {{"engine", engine}, {"variant", backend}};
    file.results.push_back(r);
    return file.results.back();
  }
  // The point's copies: their errors (the unperturbed run's first; kInf a
  // failed copy) and their total wall times.
  static void WithCopies(RunResult& r, std::vector<double> errors) {
    r.perturbed.copies = static_cast<int>(errors.size()) - 1;
    r.perturbed.amount = 1e-9;
    r.perturbed.runSeconds.assign(errors.size(), r.wallSeconds);
    double low = kInf, high = 0.0;
    int failed = 0;
    for (double e : errors) {
      if (e == kInf) {
        ++failed;
        continue;
      }
      low = std::min(low, e);
      high = std::max(high, e);
    }
    r.perturbed.errorSpread = failed == 0                                 ? high - low
                              : failed == static_cast<int>(errors.size()) ? 0.0
                                                                          : kInf;
    r.perturbed.errors = std::move(errors);
  }
  // The analysis `talus-testbed report --sweep` makes of this file once
  // written and read back.
  std::vector<SweepGroup> Analyse() const {
    auto read = ResultsFromJson(ResultsToJson(file));
    EXPECT_TRUE(read) << read.GetError().message;
    return AnalyseSweep(read.Value(), kSweepSingleSetting);
  }
};

// A copy, not a reference: callers pass the temporary Analyse() returns.
FamilyPair OnlyPair(const std::vector<SweepGroup>& groups) {
  EXPECT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups.at(0).families.pairs.size(), 1u);
  return groups.at(0).families.pairs.at(0);
}

TEST(EngineFamily, IsTheFirstWordOfTheEngineSettingElseTheBackend) {
  RunResult r;
  r.backend = "bullet-f32";
  r.settings = {{"variant", "x"}, {"engine", "Bullet 324 (single precision: the default build)"}};
  EXPECT_EQ(EngineFamily(r), "Bullet");
  r.settings = {{"engine", "Talus (double)"}};
  EXPECT_EQ(EngineFamily(r), "Talus");
  r.settings = {};
  EXPECT_EQ(EngineFamily(r), "bullet-f32");
}

// ---- One budget ----

TEST(CompareAtBudget, WorstAgainstBestDecidesAndOverlapIsATie) {
  const CostErrorPoint stable{.cost = 1, .error = 0.5};
  // Without copies the comparison is exact: 0.4 < 0.5; equal is a tie.
  const CostErrorPoint lower{.cost = 1, .error = 0.4};
  EXPECT_EQ(CompareAtBudget(&lower, &stable), BudgetOutcome::kFirst);
  EXPECT_EQ(CompareAtBudget(&stable, &lower), BudgetOutcome::kSecond);
  EXPECT_EQ(CompareAtBudget(&stable, &stable), BudgetOutcome::kTie);
  // Copies ranging over [0.3, 0.6] overlap 0.5: a tie, either way round.
  const CostErrorPoint noisy = Copies(1, 0.3, 0.3, 0.6);
  EXPECT_EQ(CompareAtBudget(&noisy, &stable), BudgetOutcome::kTie);
  EXPECT_EQ(CompareAtBudget(&stable, &noisy), BudgetOutcome::kTie);
  // A range wholly above the other's: worse, however its unperturbed run did.
  const CostErrorPoint unstable = Copies(1, 0.2, 0.2, 0.9);
  const CostErrorPoint tight{.cost = 1, .error = 0.1};
  EXPECT_EQ(CompareAtBudget(&unstable, &tight), BudgetOutcome::kSecond);
}

TEST(CompareAtBudget, AFailureOrNothingThatCheapCountsAgainstThatSide) {
  const CostErrorPoint measured{.cost = 1, .error = 5.0};
  const CostErrorPoint failedCopy = Copies(1, 0.1, 0.1, kInf);
  const CostErrorPoint crashed{.cost = 1, .error = kInf};
  EXPECT_EQ(CompareAtBudget(&failedCopy, &measured), BudgetOutcome::kSecond);
  EXPECT_EQ(CompareAtBudget(&crashed, &measured), BudgetOutcome::kSecond);
  EXPECT_EQ(CompareAtBudget(nullptr, &measured), BudgetOutcome::kSecond);
  EXPECT_EQ(CompareAtBudget(&measured, nullptr), BudgetOutcome::kFirst);
  EXPECT_EQ(CompareAtBudget(&crashed, &failedCopy), BudgetOutcome::kTie);
  EXPECT_EQ(CompareAtBudget(nullptr, nullptr), BudgetOutcome::kTie);
}

// ---- Two families ----

TEST(CompareFamilyPair, BetterAtSomeBudgetAndWorseAtNoneIsBetter) {
  // Budgets 1, 2, 4: Talus 1 < 3, 1 < 2, 0.1 < 2.
  const FamilyPair p =
      CompareFamilyPair(Family("Talus", {{1, 1.0}, {4, 0.1}}), Family("Bullet", {{1, 3.0}, {2, 2.0}}));
  EXPECT_EQ(p.outcome, PairOutcome::kFirstBetter);
  EXPECT_EQ(p.budgets, 3);
  EXPECT_EQ(p.firstWins, 3);
  EXPECT_EQ(p.secondWins, 0);
  EXPECT_FALSE(p.split);
  // Bullet's most accurate point is 2 at 2 s; Talus reaches it at 1 s.
  EXPECT_EQ(p.firstCostRatio, 0.5);
  // Talus's is 0.1 at 4 s, which Bullet never reaches.
  EXPECT_EQ(p.secondCostRatio, kInf);
}

TEST(CompareFamilyPair, EachBetterSomewhereIsASplitTieAndEqualIsATie) {
  // Talus wins at 1 (1 < 2), the peer at 4 (0.5 < 0.9).
  const FamilyPair split =
      CompareFamilyPair(Family("Talus", {{1, 1.0}, {4, 0.9}}), Family("ODE", {{1, 2.0}, {4, 0.5}}));
  EXPECT_EQ(split.outcome, PairOutcome::kTie);
  EXPECT_TRUE(split.split);
  EXPECT_EQ(split.firstWins, 1);
  EXPECT_EQ(split.secondWins, 1);
  const FamilyPair tie = CompareFamilyPair(Family("Talus", {{1, 0.5}}), Family("ODE", {{1, 0.5}}));
  EXPECT_EQ(tie.outcome, PairOutcome::kTie);
  EXPECT_FALSE(tie.split);
  EXPECT_EQ(tie.firstCostRatio, 1.0);
}

TEST(CompareFamilies, EveryFamilyAgainstEveryOtherWithTalusFirst) {
  const FamilyVerdict v = CompareFamilies({Family("Bullet", {{1, 3.0}}), Family("ODE", {{1, 2.0}}),
                                           Family("Talus", {{1, 1.0}}), Family("MuJoCo", {})});
  // MuJoCo had no point: dropped. Talus moves to the front.
  ASSERT_EQ(v.families.size(), 3u);
  EXPECT_EQ(v.families[0].family, "Talus");
  ASSERT_EQ(v.pairs.size(), 3u);
  EXPECT_EQ(v.pairs[0].first, "Talus");
  EXPECT_EQ(v.pairs[0].second, "Bullet");
  EXPECT_EQ(v.pairs[1].second, "ODE");
  // The peers against each other too: ODE's 2 beats Bullet's 3.
  EXPECT_EQ(v.pairs[2].first, "Bullet");
  EXPECT_EQ(v.pairs[2].second, "ODE");
  EXPECT_EQ(v.pairs[2].outcome, PairOutcome::kSecondBetter);
}

// ---- Issue 24's cases, through a results file ----

TEST(FamilyVerdictIssue24, AnUnstableTalusIsNotBetterThanAStablePeer) {
  // Talus's unperturbed run is 0.75 tolerances off, its copies 1.25 and 1
  // (spread 0.5); the peer is 0.25 in every copy. The old floor (margin
  // 0.5 within the spread 0.5; every number exact in binary) called this
  // "at or below"; every Talus copy is worse than every peer copy.
  FileBuilder b;
  FileBuilder::WithCopies(b.Add("talus", "Talus (double)", 0.01, 1.0, 0.75), {0.75, 1.25, 1.0});
  FileBuilder::WithCopies(b.Add("bullet", "Bullet 324", 0.01, 1.0, 0.25), {0.25, 0.25, 0.25});
  EXPECT_EQ(OnlyPair(b.Analyse()).outcome, PairOutcome::kSecondBetter);

  // Issue 24's numbers: Talus 0.9 against the peer's 0.1, its copies
  // spread 0.8 on both sides of the peer (0.1 to 0.9). Talus sometimes
  // matches it, sometimes not: a tie, never "at or below" counted as a win.
  FileBuilder overlap;
  FileBuilder::WithCopies(overlap.Add("talus", "Talus (double)", 0.01, 1.0, 0.9), {0.9, 0.1, 0.5});
  FileBuilder::WithCopies(overlap.Add("bullet", "Bullet 324", 0.01, 1.0, 0.1), {0.1, 0.1, 0.1});
  const FamilyPair tie = OnlyPair(overlap.Analyse());
  EXPECT_EQ(tie.outcome, PairOutcome::kTie);
  EXPECT_EQ(tie.firstBest, 0.1);
  EXPECT_EQ(tie.firstWorst, 0.9);
  // Copies all above the peer (0.9 to 1.7): worse.
  FileBuilder above;
  FileBuilder::WithCopies(above.Add("talus", "Talus (double)", 0.01, 1.0, 0.9), {0.9, 1.7, 1.3});
  FileBuilder::WithCopies(above.Add("bullet", "Bullet 324", 0.01, 1.0, 0.1), {0.1, 0.1, 0.1});
  EXPECT_EQ(OnlyPair(above.Analyse()).outcome, PairOutcome::kSecondBetter);
}

TEST(FamilyVerdictIssue24, AFailedCopyCountsAgainstTheSideThatHadIt) {
  // Talus 5 tolerances off with one copy failed (infinite spread, which the
  // old floor turned into a tie); the peer 0.5 in every copy.
  FileBuilder b;
  FileBuilder::WithCopies(b.Add("talus", "Talus (double)", 0.01, 1.0, 5.0), {5.0, kInf, 5.0});
  FileBuilder::WithCopies(b.Add("ode-quickstep", "ODE 0.16", 0.01, 1.0, 0.5), {0.5, 0.5, 0.5});
  const std::vector<SweepGroup> groups = b.Analyse();
  const FamilyPair& pair = OnlyPair(groups);
  EXPECT_EQ(pair.outcome, PairOutcome::kSecondBetter);
  EXPECT_EQ(pair.firstWorst, kInf);
  // Even an accurate point loses when one of its copies failed.
  FileBuilder accurate;
  FileBuilder::WithCopies(accurate.Add("talus", "Talus (double)", 0.01, 1.0, 0.01), {0.01, kInf, 0.01});
  FileBuilder::WithCopies(accurate.Add("ode-quickstep", "ODE 0.16", 0.01, 1.0, 0.5), {0.5, 0.5, 0.5});
  EXPECT_EQ(OnlyPair(accurate.Analyse()).outcome, PairOutcome::kSecondBetter);
}

TEST(FamilyVerdictIssue24, OneHundredTimesTheCostAtEqualAccuracyIsWorse) {
  // Equal errors, Talus 100 s against the peer's 1 s: at the 1 s budget
  // Talus has nothing, at 100 s they tie. The old verdict began at the
  // matched cost (100 s) and saw only the tie.
  FileBuilder b;
  b.Add("talus", "Talus (double)", 0.01, 100.0, 0.1);
  b.Add("bullet", "Bullet 324", 0.01, 1.0, 0.1);
  const std::vector<SweepGroup> groups = b.Analyse();
  const FamilyPair& pair = OnlyPair(groups);
  EXPECT_EQ(pair.outcome, PairOutcome::kSecondBetter);
  EXPECT_EQ(pair.budget, 1.0);
  EXPECT_EQ(pair.firstCostRatio, 100.0);  // Talus needs 100x the cost for the peer's error
  EXPECT_EQ(pair.secondCostRatio, 0.01);
  const std::string markdown = SweepMarkdown(groups);
  EXPECT_NE(markdown.find("| Talus | Bullet | 0 | 0 (0) | 1 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| slide | Talus | Bullet | worse | 0, 1, 2 | 1: inf, 0.1 | 100, 0.01 |"),
            std::string::npos)
      << markdown;
}

TEST(FamilyVerdictIssue24, ACheapCrashStaysInTheFrontAsInfinitelyBad) {
  // Talus: a cheap run at 1 s, then 0.1 at 10 s; the peer 0.5 at both.
  // Finishing the cheap run 3 tolerances off loses the 1 s budget; crashing
  // it must not do better (the old analysis dropped the crash, started at
  // 10 s and called Talus at or below).
  const auto verdict = [](bool crash) {
    FileBuilder b;
    RunResult& cheap = b.Add("talus", "Talus (double)", 0.1, 1.0, 3.0);
    if (crash) {
      cheap.error = "step 3: talus: non-finite position";
      cheap.metrics.clear();
    }
    b.Add("talus", "Talus (double)", 0.01, 10.0, 0.1);
    b.Add("bullet", "Bullet 324", 0.1, 1.0, 0.5);
    b.Add("bullet", "Bullet 324", 0.01, 10.0, 0.5);
    return OnlyPair(b.Analyse());
  };
  const FamilyPair finished = verdict(false);
  const FamilyPair crashed = verdict(true);
  for (const FamilyPair& pair : {finished, crashed}) {
    EXPECT_EQ(pair.outcome, PairOutcome::kTie);
    EXPECT_TRUE(pair.split);  // the peer at 1 s, Talus at 10 s
    EXPECT_EQ(pair.secondWins, 1);
    EXPECT_EQ(pair.firstWins, 1);
  }
  EXPECT_EQ(crashed.firstWorst, kInf);
  // With only the crash cheap enough, a peer that also matches Talus at
  // 10 s is simply better.
  FileBuilder b;
  RunResult& cheap = b.Add("talus", "Talus (double)", 0.1, 1.0, 0.0);
  cheap.error = "step 3: talus: non-finite position";
  cheap.metrics.clear();
  b.Add("talus", "Talus (double)", 0.01, 10.0, 0.5);
  b.Add("bullet", "Bullet 324", 0.1, 1.0, 0.5);
  EXPECT_EQ(OnlyPair(b.Analyse()).outcome, PairOutcome::kSecondBetter);
}

TEST(FamilyVerdictIssue24, ACostDifferenceWithinTheRunsTimingNoiseIsNoWin) {
  // Equal errors; Talus's median total 1.00 s (runs 0.95 to 1.05), the
  // peer's 1.01 s (0.96 to 1.06). At the 1.00 s budget one of the peer's
  // runs was that cheap, so it is not "nothing that cheap": a tie. A peer
  // whose cheapest run took 1.2 s has nothing at 1 s: Talus is better.
  const auto verdict = [](std::vector<double> peerSeconds) {
    FileBuilder b;
    RunResult& talus = b.Add("talus", "Talus (double)", 0.01, 1.00, 0.1);
    FileBuilder::WithCopies(talus, {0.1, 0.1, 0.1});
    talus.perturbed.runSeconds = {1.00, 0.95, 1.05};
    RunResult& peer = b.Add("bullet", "Bullet 324", 0.01, peerSeconds[0], 0.1);
    FileBuilder::WithCopies(peer, {0.1, 0.1, 0.1});
    peer.perturbed.runSeconds = peerSeconds;
    return OnlyPair(b.Analyse()).outcome;
  };
  EXPECT_EQ(verdict({1.01, 0.96, 1.06}), PairOutcome::kTie);
  EXPECT_EQ(verdict({1.25, 1.2, 1.3}), PairOutcome::kFirstBetter);
}

// ---- The analysis of a file ----

TEST(AnalyseSweep, AFamilysPointsAreTheUnionOfItsVariants) {
  // Talus: "talus" good cheap (0.5 at 1 s), "talus-split" good dear (0.05
  // at 4 s); Bullet: "bullet" 1 at 1 s, "bullet-f32" 0.1 at 4 s. Neither
  // Talus variant alone is better at both budgets; their union is.
  FileBuilder b;
  b.Add("talus", "Talus (double)", 0.01, 1.0, 0.5);
  b.Add("talus", "Talus (double)", 0.001, 4.0, 0.4);
  b.Add("talus-split", "Talus (double)", 0.01, 1.0, 2.0);
  b.Add("talus-split", "Talus (double)", 0.001, 4.0, 0.05);
  b.Add("bullet", "Bullet 324 (double)", 0.01, 1.0, 1.0);
  b.Add("bullet", "Bullet 324 (double)", 0.001, 4.0, 3.0);
  b.Add("bullet-f32", "Bullet 324 (single)", 0.01, 1.0, 5.0);
  b.Add("bullet-f32", "Bullet 324 (single)", 0.001, 4.0, 0.1);
  const std::vector<SweepGroup> groups = b.Analyse();
  const FamilyVerdict& v = groups.at(0).families;
  ASSERT_EQ(v.families.size(), 2u);
  EXPECT_EQ(v.families[0].backends, (std::vector<std::string>{"talus", "talus-split"}));
  const FamilyPair& pair = OnlyPair(groups);
  EXPECT_EQ(pair.outcome, PairOutcome::kFirstBetter);
  EXPECT_EQ(pair.firstWins, 2);
  const std::string json = SweepToJson(groups);
  EXPECT_NE(json.find("\"outcome\": \"better\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"firstBetter\": 1"), std::string::npos) << json;
}

TEST(AnalyseSweep, TalliesEveryPairOverTheInstancesWhereBothRan) {
  FileBuilder b;
  b.Add("talus", "Talus (double)", 0.01, 1.0, 0.5);
  b.Add("ode-quickstep", "ODE 0.16", 0.01, 1.0, 0.25);
  b.Add("bullet", "Bullet 324", 0.01, 1.0, 0.5);
  RunResult lonely = b.file.results[0];
  lonely.scenario = "lonely";
  b.file.results.push_back(lonely);
  const std::vector<SweepGroup> groups = b.Analyse();
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_TRUE(groups[1].families.pairs.empty());  // Talus alone
  const std::vector<FamilyTally> tallies = TallyFamilies(groups);
  ASSERT_EQ(tallies.size(), 3u);
  EXPECT_EQ(tallies[0].first, "Talus");
  EXPECT_EQ(tallies[0].second, "ODE");
  EXPECT_EQ(tallies[0].secondBetter, 1);
  EXPECT_EQ(tallies[1].second, "Bullet");
  EXPECT_EQ(tallies[1].ties, 1);
  EXPECT_EQ(tallies[2].first, "ODE");
  EXPECT_EQ(tallies[2].firstBetter, 1);
}

}  // namespace family_verdict_test
}  // namespace talus::harness
