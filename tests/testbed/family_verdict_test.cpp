// Issue 15's criterion in the sweep analysis (sweep.h CompareFamilies and
// its use in AnalyseSweep): Talus's engine family, the union of its
// variants' points, against every peer family at every compared budget.
// Every case is hand-made so the answer can be read off the points: which
// error is smaller at which budget, and by how much.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/sweep.h"
#include "testbed/one_metric_run.h"

namespace talus::harness {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

FamilyPoints Family(std::string name, std::vector<CostErrorPoint> points) {
  return {std::move(name), {}, std::move(points)};
}

// A results file of hand-made runs of one scenario instance, every run's
// error scalar equal to `error` (one metric, tolerance 1 absolute).
struct FileBuilder {
  ResultsFile file;
  void Add(const std::string& backend, const std::string& engine, double h, double seconds, double error) {
    if (std::find(file.backends.begin(), file.backends.end(), backend) == file.backends.end())
      file.backends.push_back(backend);
    RunResult r = testing::OneMetricRun(backend, "x", h, seconds, error);
    if (!engine.empty()) r.settings = {{"engine", engine}, {"variant", backend}};
    file.results.push_back(r);
  }
};

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

TEST(CompareFamilies, TalusBelowAtEveryBudgetIsAtOrBelow) {
  // Budgets from the matched cost 1: 1, 2, 4. Talus 1 < 3, 1 < 2, 0.1 < 2.
  const FamilyVerdict v =
      CompareFamilies({Family("Talus", {{1, 1.0}, {4, 0.1}}), Family("Bullet", {{1, 3.0}, {2, 2.0}})});
  EXPECT_EQ(v.outcome, FamilyOutcome::kAtOrBelow);
  EXPECT_EQ(v.matchedCost, 1.0);
  EXPECT_EQ(v.budgets, 3);
  ASSERT_EQ(v.peers.size(), 1u);
  EXPECT_TRUE(v.peers[0].atOrBelow);
  // The closest budget is 2: 1 - 2 = -1 (at 1: -2, at 4: -1.9).
  EXPECT_EQ(v.peers[0].budget, 2.0);
  EXPECT_EQ(v.peers[0].margin, -1.0);
}

TEST(CompareFamilies, APeerBetterAtOneBudgetIsAboveWithThatBudgetsMargin) {
  // Budgets 1, 2, 4: Talus below at 1 (1 < 2) and 4 (0.1 < 0.5), above at
  // 2, where the peer's 0.5 beats Talus's 1 by 0.5.
  const FamilyVerdict v =
      CompareFamilies({Family("Talus", {{1, 1.0}, {4, 0.1}}), Family("Bullet", {{1, 3.0}}),
                       Family("ODE", {{1, 2.0}, {2, 0.5}})});
  EXPECT_EQ(v.outcome, FamilyOutcome::kAbove);
  ASSERT_EQ(v.peers.size(), 2u);
  EXPECT_EQ(v.peers[0].family, "Bullet");
  EXPECT_TRUE(v.peers[0].atOrBelow);
  EXPECT_EQ(v.peers[1].family, "ODE");
  EXPECT_FALSE(v.peers[1].atOrBelow);
  EXPECT_EQ(v.peers[1].budget, 2.0);
  EXPECT_EQ(v.peers[1].talusError, 1.0);
  EXPECT_EQ(v.peers[1].peerError, 0.5);
  EXPECT_EQ(v.peers[1].margin, 0.5);
}

TEST(CompareFamilies, ComparesExactlyWithoutANoiseFloor) {
  // A round-off contest still counts: 1e-13 above 0.9e-13 is above, and the
  // margin says how small it is. An exact tie is at or below, margin 0.
  const FamilyVerdict above = CompareFamilies({Family("Talus", {{1, 1e-13}}), Family("ODE", {{1, 0.9e-13}})});
  EXPECT_EQ(above.outcome, FamilyOutcome::kAbove);
  EXPECT_EQ(above.peers[0].margin, 1e-13 - 0.9e-13);
  const FamilyVerdict tie = CompareFamilies({Family("Talus", {{1, 0.5}}), Family("ODE", {{1, 0.5}})});
  EXPECT_EQ(tie.outcome, FamilyOutcome::kAtOrBelow);
  EXPECT_EQ(tie.peers[0].margin, 0.0);
  // Both unmeasured (infinite) is a tie too; Talus unmeasured against a
  // finite peer is above by +infinity.
  const FamilyVerdict infinite = CompareFamilies({Family("Talus", {{1, kInf}}), Family("ODE", {{1, kInf}})});
  EXPECT_EQ(infinite.outcome, FamilyOutcome::kAtOrBelow);
  const FamilyVerdict lost = CompareFamilies({Family("Talus", {{1, kInf}}), Family("ODE", {{1, 3.0}})});
  EXPECT_EQ(lost.outcome, FamilyOutcome::kAbove);
  EXPECT_EQ(lost.peers[0].margin, kInf);
}

TEST(CompareFamilies, MissingFamiliesGiveAnOutcomeNotAVerdict) {
  const FamilyVerdict noTalus = CompareFamilies({Family("Bullet", {{1, 1.0}}), Family("ODE", {{1, 2.0}})});
  EXPECT_EQ(noTalus.outcome, FamilyOutcome::kNoTalus);
  EXPECT_TRUE(noTalus.peers.empty());
  const FamilyVerdict alone = CompareFamilies({Family("Talus", {{1, 1.0}}), Family("Bullet", {})});
  EXPECT_EQ(alone.outcome, FamilyOutcome::kNoPeer);
  EXPECT_TRUE(alone.peers.empty());
  EXPECT_EQ(CompareFamilies({}).outcome, FamilyOutcome::kNoTalus);
  // A peer family without points is skipped; the others are still judged.
  const FamilyVerdict partial =
      CompareFamilies({Family("Bullet", {}), Family("Talus", {{1, 1.0}}), Family("ODE", {{1, 2.0}})});
  EXPECT_EQ(partial.outcome, FamilyOutcome::kAtOrBelow);
  ASSERT_EQ(partial.peers.size(), 1u);
  EXPECT_EQ(partial.peers[0].family, "ODE");
}

TEST(AnalyseSweep, ATieBetweenTalusVariantsIsNoWinButAtOrBelowForTheFamily) {
  FileBuilder b;
  for (const char* variant : {"talus", "talus-split"}) {
    b.Add(variant, "Talus (double)", 0.01, 1.0, 0.2);
    b.Add(variant, "Talus (double)", 0.001, 4.0, 0.02);
  }
  b.Add("bullet", "Bullet 324 (double)", 0.01, 1.0, 0.3);
  b.Add("bullet", "Bullet 324 (double)", 0.001, 4.0, 0.05);
  const std::vector<SweepGroup> groups = AnalyseSweep(b.file, {});
  ASSERT_EQ(groups.size(), 1u);
  // Per backend, the two Talus variants tie at every budget: no winner.
  EXPECT_EQ(groups[0].comparison.winner, -1);
  const FamilyVerdict& v = groups[0].families;
  EXPECT_EQ(v.outcome, FamilyOutcome::kAtOrBelow);
  ASSERT_EQ(v.families.size(), 2u);
  EXPECT_EQ(v.families[0].backends, (std::vector<std::string>{"talus", "talus-split"}));
  EXPECT_NE(SweepMarkdown(groups).find("Talus at or below every peer family: 1 of 1 instances."),
            std::string::npos);
}

TEST(AnalyseSweep, AFamilysFrontIsTheUnionOfItsVariants) {
  // Talus: "talus" is good cheap (0.5 at 1 s) and poor dear (0.4 at 4 s),
  // "talus-split" the other way (2 at 1 s, 0.05 at 4 s). Bullet likewise:
  // "bullet" 1 at 1 s, "bullet-f32" 0.1 at 4 s. Neither Talus variant alone
  // is at or below Bullet (0.4 > 0.1 at 4 s; 2 > 1 at 1 s), their union is
  // (0.5 < 1, 0.05 < 0.1); and Bullet's union puts the closest budget at
  // 4 s (0.05 - 0.1) rather than 1 s (0.5 - 1).
  FileBuilder b;
  b.Add("talus", "Talus (double)", 0.01, 1.0, 0.5);
  b.Add("talus", "Talus (double)", 0.001, 4.0, 0.4);
  b.Add("talus-split", "Talus (double)", 0.01, 1.0, 2.0);
  b.Add("talus-split", "Talus (double)", 0.001, 4.0, 0.05);
  b.Add("bullet", "Bullet 324 (double)", 0.01, 1.0, 1.0);
  b.Add("bullet", "Bullet 324 (double)", 0.001, 4.0, 3.0);
  b.Add("bullet-f32", "Bullet 324 (single)", 0.01, 1.0, 5.0);
  b.Add("bullet-f32", "Bullet 324 (single)", 0.001, 4.0, 0.1);
  const std::vector<SweepGroup> groups = AnalyseSweep(b.file, {});
  ASSERT_EQ(groups.size(), 1u);
  const FamilyVerdict& v = groups[0].families;
  EXPECT_EQ(v.outcome, FamilyOutcome::kAtOrBelow);
  ASSERT_EQ(v.peers.size(), 1u);
  EXPECT_EQ(v.peers[0].family, "Bullet");
  EXPECT_EQ(v.peers[0].budget, 4.0);
  EXPECT_EQ(v.peers[0].talusError, 0.05);
  EXPECT_EQ(v.peers[0].peerError, 0.1);
  const std::string json = SweepToJson(groups);
  EXPECT_NE(json.find("\"outcome\": \"at or below every peer\""), std::string::npos);
  EXPECT_NE(json.find("\"atOrBelowEveryPeer\": 1"), std::string::npos);
}

TEST(AnalyseSweep, CountsOnlyInstancesWithTalusAndAPeer) {
  FileBuilder b;
  b.Add("talus", "Talus (double)", 0.01, 1.0, 0.5);
  b.Add("ode-quickstep", "ODE 0.16", 0.01, 1.0, 0.25);
  RunResult lonely = b.file.results[0];
  lonely.scenario = "lonely";
  b.file.results.push_back(lonely);
  const std::vector<SweepGroup> groups = AnalyseSweep(b.file, {});
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].families.outcome, FamilyOutcome::kAbove);
  EXPECT_EQ(groups[0].families.peers[0].margin, 0.25);
  EXPECT_EQ(groups[1].families.outcome, FamilyOutcome::kNoPeer);
  const std::string markdown = SweepMarkdown(groups);
  EXPECT_NE(markdown.find("Talus at or below every peer family: 0 of 1 instances (1 more without both Talus "
                          "and a peer result)."),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("| slide | above a peer | 1 | ODE (above): 1, 0.5, 0.25, 0.25, 0 |"),
            std::string::npos)
      << markdown;
}

}  // namespace
}  // namespace talus::harness
