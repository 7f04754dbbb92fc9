// The large-scenes section of the report: talus-scenes's JSON lines read
// back exactly (round trip, stage times, thread counts and solver settings
// included), malformed or inconsistent lines refused with the line and the
// key, the tables' ratios against Bullet by total time, where each stage's
// time goes, thread speed-ups, speed against accuracy over solver settings,
// the goal verdicts (met, missed, worse) and the section in summary.md and
// report.html only when given.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "talus/harness/report/bench_summary.h"
#include "talus/harness/report/report.h"
#include "talus/harness/scenes/bench_report_json.h"

namespace talus::harness {
namespace bench_section_test {

// The cost of a 600-step run whose mean step is `meanMs`: total 600 x mean,
// and a longest (landing) step of three means.
void SetCost(BenchReport& r, double meanMs) {
  r.steps = 600;
  r.msMean = meanMs;
  r.totalMs = meanMs * 600.0;
  r.msMax = meanMs * 3.0;
}

BenchReport Pyramid(const std::string& engine, int h, double meanMs, double drift) {
  BenchReport r;
  r.engine = engine;
  r.scene = "pyramid";
  r.parameter = h;
  r.bodies = PyramidCubeCount(h);
  SetCost(r, meanMs);
  r.maxContacts = 100 * h;
  r.drift = drift;
  return r;
}

BenchReport Pile(const std::string& engine, int l, double meanMs, double penetration, int escaped) {
  BenchReport r;
  r.engine = engine;
  r.scene = "hull_pile";
  r.parameter = l;
  r.bodies = 10 * l * l;
  SetCost(r, meanMs);
  r.maxContacts = 40 * l * l;
  r.maxPenetration = penetration;
  r.kineticEnergy = 1.5;
  r.escaped = escaped;
  return r;
}

TEST(BenchReportJson, EveryFieldSurvivesTheRoundTripExactly) {
  BenchReport skipped = Pyramid("ode-step", 15, 0.0, 0.0);
  skipped.skipped = "dWorldStep is dense: \"too big\"";
  BenchReport nan = Pile("talus", 10, 72.5, 0.0431, 0);
  nan.kineticEnergy = std::numeric_limits<double>::quiet_NaN();
  BenchReport third = Pyramid("talus", 15, 1.0, 1.5e-3);
  third.totalMs = 200.0;  // 600 steps
  third.msMean = third.totalMs / 600.0;
  third.msMax = 2.0 / 3.0;
  third.solver = {8, 2};
  const std::vector<BenchReport> written = {third, skipped, nan};
  std::string text;
  for (const BenchReport& r : written) text += BenchReportToJson(r) + "\n\n";
  auto read = ParseBenchReportLines(text, "mem");
  ASSERT_TRUE(read) << read.GetError().message;
  ASSERT_EQ(read.Value().size(), written.size());
  const BenchReport& a = read.Value()[0];
  EXPECT_EQ(a.engine, "talus");
  EXPECT_EQ(a.bodies, 1240);
  // exact: JSON keeps 17 significant digits
  EXPECT_EQ(a.totalMs, 200.0);
  EXPECT_EQ(a.msMean, 200.0 / 600.0);
  EXPECT_EQ(a.msMax, 2.0 / 3.0);
  EXPECT_EQ(a.solver.iterations, 8);
  EXPECT_EQ(a.solver.substeps, 2);
  EXPECT_EQ(a.drift, 1.5e-3);
  EXPECT_FALSE(a.maxPenetration.has_value());
  EXPECT_EQ(read.Value()[1].skipped, skipped.skipped);
  EXPECT_EQ(read.Value()[1].solver.iterations, 0);  // the engine's default
  EXPECT_EQ(read.Value()[1].solver.substeps, 1);
  EXPECT_FALSE(read.Value()[1].drift.has_value());
  const BenchReport& c = read.Value()[2];
  ASSERT_TRUE(c.kineticEnergy.has_value());
  EXPECT_TRUE(std::isnan(*c.kineticEnergy));  // written as null, read as NaN
  EXPECT_EQ(c.escaped, 0);
}

TEST(BenchReportJson, MalformedLinesAreRefusedWithLineAndKey) {
  const std::string good = BenchReportToJson(Pyramid("talus", 4, 1.0, 0.0));
  const auto message = [](const std::string& text) {
    auto read = ParseBenchReportLines(text, "scenes.jsonl");
    return read ? std::string("accepted") : read.GetError().message;
  };
  ASSERT_EQ(message(good), "accepted");
  EXPECT_EQ(message(good + "\n{oops"), "scenes.jsonl:2: not valid JSON");
  EXPECT_EQ(message(R"({"engine":"talus","scene":"pyramid","parameter":4,"threads":1,"steps":6})"),
            "scenes.jsonl:1: $.bodies: missing");
  std::string negative = good;
  negative.replace(negative.find("\"bodies\":30"), 11, "\"bodies\":-3");
  EXPECT_EQ(message(negative), "scenes.jsonl:1: $.bodies: expected an integer >= 0");
  std::string text = good;
  text.replace(text.find("\"total_ms\":600.0"), 16, "\"total_ms\":\"x\"");
  EXPECT_EQ(message(text), "scenes.jsonl:1: $.total_ms: expected a finite number >= 0");
  auto missing = ReadBenchReportFile("/nonexistent/scenes.jsonl");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("/nonexistent/scenes.jsonl"), std::string::npos);
}

// A file from before the cost was the total time (a median over the steps)
// is refused, not read with a cost of 0.
TEST(BenchReportJson, AMedianStepFileIsRefused) {
  EXPECT_EQ(ParseBenchReportLines(
                R"({"engine":"talus","scene":"pyramid","parameter":4,"bodies":30,"threads":1,"steps":60,)"
                R"("iterations":0,"substeps":1,"ms_per_step_median":1.0,"ms_per_step_mean":1.2,)"
                R"("max_contacts":496,"drift_m":0.001})",
                "old.jsonl")
                .GetError()
                .message,
            "old.jsonl:1: $.total_ms: missing");
}

// The three times must hang together (mean = total / steps, mean <= longest
// <= total), and the settings must be ones the engine has: a line edited by
// hand, or one that claims iterations of a direct solver, is refused.
TEST(BenchReportJson, CostsThatDoNotAddUpAndSettingsAnEngineLacksAreRefused) {
  const std::string good = BenchReportToJson(Pyramid("talus", 4, 1.0, 0.0));  // total 600, mean 1, max 3
  const auto message = [&good](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " in " << good;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    auto read = ParseBenchReportLines(text, "scenes.jsonl");
    return read ? std::string("accepted") : read.GetError().message;
  };
  EXPECT_EQ(message("\"total_ms\":600.0", "\"total_ms\":300.0"),
            "scenes.jsonl:1: $.ms_per_step_mean: expected total_ms / steps");
  EXPECT_EQ(message("\"steps\":600", "\"steps\":0"),
            "scenes.jsonl:1: $.steps: expected at least 1 step in a run that was made");
  EXPECT_EQ(
      message("\"ms_per_step_max\":3.0", "\"ms_per_step_max\":0.5"),
      "scenes.jsonl:1: $.ms_per_step_max: expected a longest step between ms_per_step_mean and total_ms");
  EXPECT_EQ(
      message("\"ms_per_step_max\":3.0", "\"ms_per_step_max\":601.0"),
      "scenes.jsonl:1: $.ms_per_step_max: expected a longest step between ms_per_step_mean and total_ms");
  // The rounding of a sum is not a forgery: 1e-10 relative is accepted.
  EXPECT_EQ(message("\"total_ms\":600.0", "\"total_ms\":600.00000006"), "accepted");
  EXPECT_EQ(message("\"substeps\":1", "\"substeps\":0"),
            "scenes.jsonl:1: $.substeps: expected a setting the engine has: substeps 0: must be in [1, 100]");
  EXPECT_EQ(
      message("\"iterations\":0", "\"iterations\":1001"),
      "scenes.jsonl:1: $.iterations: expected a setting the engine has: iterations 1001: must be in [0, "
      "1000] (0: the engine's default)");
  // ode-step at its own (only) setting is fine; asked for iterations, not.
  EXPECT_EQ(message("\"engine\":\"talus\"", "\"engine\":\"ode-step\""), "accepted");
  BenchReport odeStep = Pyramid("ode-step", 4, 1.0, 0.0);
  std::string odeText = BenchReportToJson(odeStep);
  odeText.replace(odeText.find("\"iterations\":0"), std::string("\"iterations\":0").size(),
                  "\"iterations\":20");
  EXPECT_EQ(ParseBenchReportLines(odeText, "scenes.jsonl").GetError().message,
            "scenes.jsonl:1: $.iterations: expected a setting the engine has: iterations 20: ode-step has no "
            "iteration count (dWorldStep solves each island directly, a Dantzig LCP)");
}

// Stage times in a 600-step run of `engine` at `threads` on pyramid H =
// `h`: each stage {name, mean ms, longest ms}, and the step's mean (its
// longest is three means).
BenchReport Staged(const std::string& engine, int h, int threads, double msMean,
                   std::vector<BenchStage> stages) {
  BenchReport r = Pyramid(engine, h, msMean, 0.001);
  r.threads = threads;
  r.stages = std::move(stages);
  return r;
}

TEST(BenchReportJson, StagesAndThreadsSurviveTheRoundTripExactly) {
  const BenchReport written =
      Staged("talus-coloured", 20, 2, 50.0, {{"FindContacts", 1.0 / 3.0, 0.4}, {"UpdateSleep", 0.0, 0.0}});
  auto read = ParseBenchReportLines(
      BenchReportToJson(written) + "\n" + BenchReportToJson(Pyramid("bullet", 20, 9.0, 0.0)), "mem");
  ASSERT_TRUE(read) << read.GetError().message;
  const BenchReport& a = read.Value()[0];
  EXPECT_EQ(a.threads, 2);
  ASSERT_EQ(a.stages.size(), 2u);
  EXPECT_EQ(a.stages[0].name, "FindContacts");
  EXPECT_EQ(a.stages[0].msMean, 1.0 / 3.0);  // exact: JSON keeps 17 significant digits
  EXPECT_EQ(a.stages[0].msMax, 0.4);
  EXPECT_EQ(a.stages[1].name, "UpdateSleep");
  EXPECT_EQ(a.stages[1].msMax, 0.0);
  EXPECT_TRUE(read.Value()[1].stages.empty());  // a peer's line has no "stages"
  EXPECT_EQ(BenchReportToJson(Pyramid("bullet", 20, 9.0, 0.0)).find("stages"), std::string::npos);
}

TEST(BenchReportJson, BadStageTimesAreRefusedWithLineAndKey) {
  // Step mean 2 ms, longest 6 ms.
  const std::string good = BenchReportToJson(
      Staged("talus", 4, 1, 2.0, {{"FindContacts", 1.0, 1.0}, {"SolveVelocities", 0.5, 0.5}}));
  const auto message = [](const std::string& text) {
    auto read = ParseBenchReportLines(text, "scenes.jsonl");
    return read ? std::string("accepted") : read.GetError().message;
  };
  ASSERT_EQ(message(good), "accepted");
  const auto replaced = [&good](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " in " << good;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  // A stage time written as null (a NaN) or missing, a stage without a name
  // or named twice, "stages" that is not a list, stages whose means add up
  // to more than the step they ran inside, and a stage's longest step
  // longer than the longest step.
  EXPECT_EQ(message(replaced("\"ms_max\":0.5", "\"ms_max\":null")),
            "scenes.jsonl:1: $.stages[1].ms_max: expected a finite number >= 0");
  EXPECT_EQ(message(replaced(",\"ms_max\":1.0", "")), "scenes.jsonl:1: $.stages[0].ms_max: missing");
  EXPECT_EQ(message(replaced("\"ms_mean\":0.5", "\"ms_mean\":-0.5")),
            "scenes.jsonl:1: $.stages[1].ms_mean: expected a finite number >= 0");
  EXPECT_EQ(message(replaced("\"ms_max\":0.5", "\"ms_max\":6.5")),
            "scenes.jsonl:1: $.stages[1].ms_max: expected a longest step no longer than ms_per_step_max");
  EXPECT_EQ(message(replaced("\"stage\":\"SolveVelocities\"", "\"stage\":\"\"")),
            "scenes.jsonl:1: $.stages[1].stage: expected a non-empty string");
  EXPECT_EQ(message(replaced("\"stage\":\"SolveVelocities\"", "\"stage\":\"FindContacts\"")),
            "scenes.jsonl:1: $.stages[1].stage: expected a stage named once");
  const std::size_t list = good.find("\"stages\":");
  EXPECT_EQ(message(good.substr(0, list) + "\"stages\":{}}"), "scenes.jsonl:1: $.stages: expected an array");
  EXPECT_EQ(message(replaced("\"ms_mean\":0.5", "\"ms_mean\":1.5")),
            "scenes.jsonl:1: $.stages: expected stage means adding up to at most ms_per_step_mean");
}

// One thread and two threads of talus-coloured on pyramid H = 20 (and a
// hull_pile pair for the other goal): times chosen so every cell is known.
std::vector<BenchReport> ThreadedRuns() {
  BenchReport pile1 = Pile("talus-coloured", 20, 100.0, 0.01, 0);
  BenchReport pile2 = pile1;
  pile2.threads = 2;
  SetCost(pile2, 55.0);
  return {Staged("talus-coloured", 20, 1, 80.0,
                 {{"FindContacts", 20.0, 60.0}, {"SolveVelocities", 48.0, 200.0}, {"UpdateSleep", 2.0, 2.0}}),
          Staged("talus-coloured", 20, 2, 50.0,
                 {{"FindContacts", 10.0, 30.0}, {"SolveVelocities", 30.0, 140.0}, {"UpdateSleep", 1.0, 1.0}}),
          Pyramid("bullet", 20, 90.0, 0.01), pile1, pile2};
}

TEST(BenchSection, WhereTheTimeGoesGivesEachStageItsMeanShareLongestStepAndSpeedup) {
  const std::string md = BenchMarkdown(ThreadedRuns());
  const std::size_t heading = md.find(
      "\n### pyramid H = 20: where the time goes\n\n"
      "| stage | talus-coloured | talus-coloured, 2 threads | talus-coloured: speed-up "
      "at 2 threads |\n|---|---|---|---|\n");
  ASSERT_NE(heading, std::string::npos) << md;
  // Shares are stage mean / step mean: 20/80, 48/80, 2/80 and 10/50, 30/50,
  // 1/50; "other" is what the stages leave of the mean (10/80, 9/50); the
  // speed-ups divide the means (20/10, 48/30, 2/1) and the totals (80 x 600
  // / 50 x 600); the step's longest is three means (Staged).
  EXPECT_NE(md.find("| FindContacts | 20 (25.0%; max 60) | 10 (20.0%; max 30) | 2 |\n"
                    "| SolveVelocities | 48 (60.0%; max 200) | 30 (60.0%; max 140) | 1.6 |\n"
                    "| UpdateSleep | 2 (2.5%; max 2) | 1 (2.0%; max 1) | 2 |\n"
                    "| other (outside the stages) | (12.5%) | (18.0%) | - |\n"
                    "| step | 80 (100%; max 240) | 50 (100%; max 150) | 1.6 |\n",
                    heading),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("\n### Where the time goes\n"), std::string::npos) << md;
  EXPECT_NE(md.find("[where the time goes](#where-the-time-goes)"), std::string::npos) << md;
  // Bullet times no stages and the hull pile runs here have none: no column, no table.
  EXPECT_EQ(md.find("hull_pile L = 20: where the time goes"), std::string::npos) << md;
}

TEST(BenchSection, ThreadScalingAndTheTwoThreadGoalCompareTotalsOfOneEngine) {
  const std::string md = BenchMarkdown(ThreadedRuns());
  EXPECT_NE(md.find("| pyramid H = 20 | talus-coloured | 1 | 80 | 1 |\n"
                    "| pyramid H = 20 | talus-coloured | 2 | 50 | 1.6 |\n"
                    "| hull_pile L = 20 | talus-coloured | 1 | 100 | 1 |\n"
                    "| hull_pile L = 20 | talus-coloured | 2 | 55 | 1.82 |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- pyramid H = 20: talus-coloured at 1 / 2 threads = 1.6 (goal >= 1.7: missed)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- hull_pile L = 20: talus-coloured at 1 / 2 threads = 1.82 (goal >= 1.7: met)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("[Thread scaling](#thread-scaling)"), std::string::npos);
  // The main table names the 2-thread run: 600 steps, 30 s in all, 50 ms a
  // step, 150 the longest; Bullet's ratio column divides the totals.
  EXPECT_NE(md.find("| 20 | 2870 | talus-coloured, 2 threads | 600 | 30 | 50 | 150 | 0.556 (bullet) |"),
            std::string::npos)
      << md;
  // The scorecard's column is one engine on one thread, its mean step.
  const std::vector<BenchHeadline> headlines = BenchHeadlines(ThreadedRuns());
  ASSERT_EQ(headlines.size(), 2u);
  EXPECT_EQ(headlines[0].title, "pyramid H = 20 (mean ms/step)");
  EXPECT_EQ(headlines[0].cellByEngine.at("talus-coloured"), "80");
  EXPECT_EQ(headlines[1].cellByEngine.at("talus-coloured"), "100");
}

TEST(BenchSection, OneThreadCountAndNoStagesAddNoStageOrThreadSection) {
  const std::string md = BenchMarkdown({Pyramid("talus", 15, 9.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07)});
  EXPECT_EQ(md.find("where the time goes"), std::string::npos) << md;
  EXPECT_EQ(md.find("Thread scaling"), std::string::npos) << md;
  EXPECT_EQ(md.find("threads ="), std::string::npos) << md;
  EXPECT_EQ(md.find("Speed against accuracy"), std::string::npos) << md;
}

TEST(BenchSection, RatiosDivideTotalsByBulletOfTheSameSceneAndParameter) {
  const std::vector<BenchReport> reports = {
      Pyramid("talus", 15, 30.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07), Pyramid("talus", 10, 4.0, 0.001),
      Pyramid("bullet", 10, 8.0, 0.01)};
  const std::string md = BenchMarkdown(reports);
  // Rows by parameter, then engine in first-seen order: steps, total (s),
  // mean and longest step (ms), total / Bullet's total.
  const std::size_t h10 = md.find("| 10 | 385 | talus | 600 | 2.4 | 4 | 12 | 0.5 (bullet) |");
  const std::size_t h15 = md.find("| 15 | 1240 | talus | 600 | 18 | 30 | 90 | 1.5 (bullet) |");
  ASSERT_NE(h10, std::string::npos) << md;
  ASSERT_NE(h15, std::string::npos) << md;
  EXPECT_LT(h10, h15);
  EXPECT_NE(md.find("| 15 | 1240 | bullet | 600 | 12 | 20 | 60 | 1 (bullet) |"), std::string::npos) << md;
}

// The cost is the whole run: a run whose landing steps are slow costs more
// however fast its typical step is, and runs of different lengths are not
// divided by each other.
TEST(BenchSection, TheRatioIsTheTotalTimeOverTheSameSteps) {
  BenchReport spiky = Pyramid("talus", 15, 10.0, 0.001);
  spiky.totalMs = 9000.0;  // 15 ms a step on average: some landing steps cost far more than the rest
  spiky.msMean = 15.0;
  spiky.msMax = 400.0;
  BenchReport shortRun = Pyramid("bullet-f32", 15, 1.0, 0.07);
  shortRun.steps = 60;
  shortRun.totalMs = 60.0;
  const std::string md = BenchMarkdown({spiky, Pyramid("bullet", 15, 12.0, 0.07), shortRun});
  // 9000 / 7200, against the 600-step Bullet run, not the 60-step one.
  EXPECT_NE(md.find("| 15 | 1240 | talus | 600 | 9 | 15 | 400 | 1.25 (bullet) |"), std::string::npos) << md;
  EXPECT_NE(md.find("- pyramid H = 15: talus / bullet (the fastest bullet), total time over 600 steps = 1.25 "
                    "(goal <= 0.5: missed)"),
            std::string::npos)
      << md;
}

TEST(BenchSection, RatiosDivideByTheFastestBulletConfiguration) {
  // Four Bullet configurations ran; the single-precision tuned one is the
  // fastest at H = 15 and the double defaults at H = 10, and each row says
  // which it divided by. Another engine family ("ode-...") is never the peer.
  const std::vector<BenchReport> reports = {Pyramid("talus", 15, 30.0, 0.001),
                                            Pyramid("bullet", 15, 20.0, 0.07),
                                            Pyramid("bullet-f32-tuned", 15, 12.0, 0.07),
                                            Pyramid("bullet-tuned", 15, 19.0, 0.07),
                                            Pyramid("ode-quickstep", 15, 1.0, 0.07),
                                            Pyramid("talus", 10, 4.0, 0.001),
                                            Pyramid("bullet", 10, 8.0, 0.01),
                                            Pyramid("bullet-f32", 10, 9.0, 0.01)};
  const std::string md = BenchMarkdown(reports);
  EXPECT_NE(md.find("| 15 | 1240 | talus | 600 | 18 | 30 | 90 | 2.5 (bullet-f32-tuned) |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 10 | 385 | talus | 600 | 2.4 | 4 | 12 | 0.5 (bullet) |"), std::string::npos) << md;
  EXPECT_NE(md.find("talus / bullet-f32-tuned (the fastest bullet), total time over 600 steps = 2.5"),
            std::string::npos)
      << md;
}

TEST(BenchSection, GoalsSayMetMissedAndWhetherStabilityIsWorse) {
  const std::vector<BenchReport> reports = {
      Pyramid("talus", 15, 9.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07), Pile("talus", 10, 30.0, 0.04, 0),
      Pile("bullet", 10, 40.0, 0.005, 0)};
  const std::string md = BenchMarkdown(reports);
  EXPECT_NE(md.find("- pyramid H = 15: talus / bullet (the fastest bullet), total time over 600 steps = 0.45 "
                    "(goal <= 0.5: met); drift 0.001 m vs 0.07 m (no worse)"),
            std::string::npos)
      << md;
  EXPECT_NE(
      md.find("- hull_pile L = 10: talus / bullet (the fastest bullet), total time over 600 steps = 0.75 "
              "(goal <= 0.5: missed); max penetration 0.04 m vs 0.005 m (worse)"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("escaped 0 vs 0 (no worse)"), std::string::npos);
}

// Runs at other solver settings are named with them, and neither set the
// ratio's denominator nor stand for the engine in the goals and the
// scorecard: those judge each engine at its own defaults.
BenchReport WithSolver(BenchReport r, int iterations, int substeps, double meanMs, double figure) {
  r.solver = {iterations, substeps};
  SetCost(r, meanMs);
  if (r.drift) r.drift = figure;
  if (r.maxPenetration) r.maxPenetration = figure;
  return r;
}

std::vector<BenchReport> SettingsRuns() {
  const BenchReport talus = Pyramid("talus", 15, 30.0, 0.002);
  const BenchReport bullet = Pyramid("bullet", 15, 20.0, 0.07);
  return {talus,
          WithSolver(talus, 4, 1, 15.0, 0.004),
          WithSolver(talus, 20, 1, 50.0, 0.003),  // slower and less accurate than the default: off the front
          bullet,
          WithSolver(bullet, 20, 1, 35.0, 0.01),
          WithSolver(bullet, 5, 2, 5.0, 0.09)};
}

TEST(BenchSection, OtherSolverSettingsAreNamedAndLeftOutOfRatiosAndGoals) {
  const std::vector<BenchReport> reports = SettingsRuns();
  const std::string md = BenchMarkdown(reports);
  // Bullet's 5-iteration 2-substep run is the fastest Bullet, but not at its defaults.
  EXPECT_NE(md.find("| 15 | 1240 | talus | 600 | 18 | 30 | 90 | 1.5 (bullet) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 15 | 1240 | bullet, 5 iterations, 2 substeps | 600 | 3 | 5 | 15 | 0.25 (bullet) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 15 | 1240 | talus, 4 iterations | 600 | 9 | 15 | 45 | 0.75 (bullet) |"),
            std::string::npos)
      << md;
  EXPECT_NE(
      md.find("- pyramid H = 15: talus / bullet (the fastest bullet), total time over 600 steps = 1.5 "),
      std::string::npos)
      << md;
  const std::vector<BenchHeadline> headlines = BenchHeadlines(reports);
  ASSERT_EQ(headlines.size(), 1u);
  EXPECT_EQ(headlines[0].cellByEngine.at("talus"), "30");
  EXPECT_EQ(headlines[0].cellByEngine.at("bullet"), "20");
}

TEST(BenchSection, SpeedAgainstAccuracyListsEveryRunAndMarksEachEnginesFront) {
  const std::string md = BenchMarkdown(SettingsRuns());
  const std::size_t table = md.find(
      "\n### pyramid H = 15: speed against accuracy\n\n| engine | settings | steps | total (s) | ms/step "
      "(mean) | "
      "longest step (ms) | drift (m) | on its front |\n|---|---|---|---|---|---|---|---|\n");
  ASSERT_NE(table, std::string::npos) << md;
  // talus: 4 iterations (9 s, 4 mm) and the default (18 s, 2 mm) trade time
  // for drift; 20 iterations (30 s, 3 mm) is beaten on both by the default.
  // bullet: each of its three is on its front (faster ones drift more).
  EXPECT_NE(md.find("| talus | engine default | 600 | 18 | 30 | 90 | 0.002 | yes |\n"
                    "| talus | 4 iterations | 600 | 9 | 15 | 45 | 0.004 | yes |\n"
                    "| talus | 20 iterations | 600 | 30 | 50 | 150 | 0.003 | no |\n"
                    "| bullet | engine default | 600 | 12 | 20 | 60 | 0.07 | yes |\n"
                    "| bullet | 20 iterations | 600 | 21 | 35 | 105 | 0.01 | yes |\n"
                    "| bullet | 5 iterations, 2 substeps | 600 | 3 | 5 | 15 | 0.09 | yes |\n",
                    table),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("[Speed against accuracy](#speed-against-accuracy)"), std::string::npos) << md;
  const std::string html = BenchHtmlSection(SettingsRuns());
  EXPECT_NE(html.find("id=\"scenes-tradeoff-data\""), std::string::npos);
  EXPECT_NE(html.find("\"settings\":\"5 iterations, 2 substeps\""), std::string::npos) << html;
  EXPECT_EQ(BenchHtmlSection({Pyramid("talus", 15, 9.0, 0.001)}).find("scenes-tradeoff"), std::string::npos);
}

TEST(BenchSection, SkippedRunsSayWhyAndLeaveNoGoalWithoutBothEngines) {
  BenchReport skipped = Pyramid("ode-step", 15, 0.0, 0.0);
  skipped.skipped = "too many bodies";
  const std::string md = BenchMarkdown({Pyramid("talus", 15, 9.0, 0.001), skipped});
  EXPECT_NE(md.find("| 15 | 1240 | ode-step | 600 | skipped: too many bodies |"), std::string::npos) << md;
  EXPECT_EQ(md.find("### Goals"), std::string::npos);  // no Bullet run to compare with
  EXPECT_NE(md.find("| 15 | 1240 | talus | 600 | 5.4 | 9 | 27 | - |"), std::string::npos) << md;
}

TEST(BenchSection, ReportHasTheSectionAndChartsOnlyWhenGiven) {
  const std::vector<BenchReport> reports = {Pyramid("talus", 15, 9.0, 0.001),
                                            Pyramid("bullet", 15, 20.0, 0.07)};
  const ResultsFile file;
  EXPECT_EQ(SummaryMarkdown(file).find("## Large scenes"), std::string::npos);
  EXPECT_EQ(ReportHtml(file, "").find("scenes-data"), std::string::npos);
  EXPECT_NE(SummaryMarkdown(file, {.scenes = &reports}).find("## Large scenes"), std::string::npos);
  const std::string html = ReportHtml(file, "", "", {.scenes = &reports});
  EXPECT_NE(html.find("<h2 id=\"large-scenes\">Large scenes</h2>"), std::string::npos);
  EXPECT_NE(html.find("id=\"scenes-data\""), std::string::npos);
  EXPECT_NE(html.find("id=\"scenes-plots\""), std::string::npos);
  EXPECT_TRUE(BenchHtmlSection({}).empty());
  EXPECT_TRUE(BenchMarkdown({}).empty());
}

}  // namespace bench_section_test
}  // namespace talus::harness
