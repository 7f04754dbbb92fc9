// The large-scenes section of the report: talus-scenes's JSON lines read
// back exactly (round trip, stage times and thread counts included),
// malformed lines refused with the line and the key, the tables' ratios
// against Bullet, where each stage's time goes, thread speed-ups, the goal verdicts (met, missed,
// worse) and the section in summary.md and report.html only when given.
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
namespace {

BenchReport Pyramid(const std::string& engine, int h, double ms, double drift) {
  BenchReport r;
  r.engine = engine;
  r.scene = "pyramid";
  r.parameter = h;
  r.bodies = PyramidCubeCount(h);
  r.steps = 600;
  r.msMedian = ms;
  r.msMean = ms * 1.1;
  r.maxContacts = 100 * h;
  r.drift = drift;
  return r;
}

BenchReport Pile(const std::string& engine, int l, double ms, double penetration, int escaped) {
  BenchReport r;
  r.engine = engine;
  r.scene = "hull_pile";
  r.parameter = l;
  r.bodies = 10 * l * l;
  r.steps = 600;
  r.msMedian = ms;
  r.msMean = ms;
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
  const std::vector<BenchReport> written = {Pyramid("talus", 15, 1.0 / 3.0, 1.5e-3), skipped, nan};
  std::string text;
  for (const BenchReport& r : written) text += BenchReportToJson(r) + "\n\n";
  auto read = ParseBenchReportLines(text, "mem");
  ASSERT_TRUE(read) << read.GetError().message;
  ASSERT_EQ(read.Value().size(), written.size());
  const BenchReport& a = read.Value()[0];
  EXPECT_EQ(a.engine, "talus");
  EXPECT_EQ(a.bodies, 1240);
  EXPECT_EQ(a.msMedian, 1.0 / 3.0);  // exact: JSON keeps 17 significant digits
  EXPECT_EQ(a.drift, 1.5e-3);
  EXPECT_FALSE(a.maxPenetration.has_value());
  EXPECT_EQ(read.Value()[1].skipped, skipped.skipped);
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
  EXPECT_EQ(message(good + "\n{oops"), "scenes.jsonl:2: not valid JSON");
  EXPECT_EQ(message(R"({"engine":"talus","scene":"pyramid","parameter":4,"threads":1,"steps":6})"),
            "scenes.jsonl:1: $.bodies: missing");
  std::string negative = good;
  negative.replace(negative.find("\"bodies\":30"), 11, "\"bodies\":-3");
  EXPECT_EQ(message(negative), "scenes.jsonl:1: $.bodies: expected an integer >= 0");
  std::string text = good;
  text.replace(text.find("\"ms_per_step_median\":1.0"), 24, "\"ms_per_step_median\":\"x\"");
  EXPECT_EQ(message(text), "scenes.jsonl:1: $.ms_per_step_median: expected a number or null");
  auto missing = ReadBenchReportFile("/nonexistent/scenes.jsonl");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("/nonexistent/scenes.jsonl"), std::string::npos);
}

// Stage times in a run of `engine` at `threads` on pyramid H = `h`: each
// stage {name, median ms, mean ms}, and the step's median and mean.
BenchReport Staged(const std::string& engine, int h, int threads, double msMedian, double msMean,
                   std::vector<BenchStage> stages) {
  BenchReport r = Pyramid(engine, h, msMedian, 0.001);
  r.threads = threads;
  r.msMean = msMean;
  r.stages = std::move(stages);
  return r;
}

TEST(BenchReportJson, StagesAndThreadsSurviveTheRoundTripExactly) {
  const BenchReport written = Staged("talus-coloured", 20, 2, 50.0, 50.5,
                                     {{"FindContacts", 1.0 / 3.0, 0.4}, {"UpdateSleep", 0.0, 0.0}});
  auto read = ParseBenchReportLines(
      BenchReportToJson(written) + "\n" + BenchReportToJson(Pyramid("bullet", 20, 9.0, 0.0)), "mem");
  ASSERT_TRUE(read) << read.GetError().message;
  const BenchReport& a = read.Value()[0];
  EXPECT_EQ(a.threads, 2);
  ASSERT_EQ(a.stages.size(), 2u);
  EXPECT_EQ(a.stages[0].name, "FindContacts");
  EXPECT_EQ(a.stages[0].msMedian, 1.0 / 3.0);  // exact: JSON keeps 17 significant digits
  EXPECT_EQ(a.stages[0].msMean, 0.4);
  EXPECT_EQ(a.stages[1].name, "UpdateSleep");
  EXPECT_EQ(a.stages[1].msMean, 0.0);
  EXPECT_TRUE(read.Value()[1].stages.empty());  // a peer's line has no "stages"
  EXPECT_EQ(BenchReportToJson(Pyramid("bullet", 20, 9.0, 0.0)).find("stages"), std::string::npos);
}

TEST(BenchReportJson, BadStageTimesAreRefusedWithLineAndKey) {
  const std::string good = BenchReportToJson(
      Staged("talus", 4, 1, 2.0, 2.0, {{"FindContacts", 1.0, 1.0}, {"SolveVelocities", 0.5, 0.5}}));
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
  // or named twice, "stages" that is not a list, and stages whose means add
  // up to more than the step they ran inside.
  EXPECT_EQ(message(replaced("\"ms_median\":0.5", "\"ms_median\":null")),
            "scenes.jsonl:1: $.stages[1].ms_median: expected a finite number >= 0");
  EXPECT_EQ(message(replaced("\"ms_median\":1.0,", "")), "scenes.jsonl:1: $.stages[0].ms_median: missing");
  EXPECT_EQ(message(replaced("\"ms_mean\":0.5", "\"ms_mean\":-0.5")),
            "scenes.jsonl:1: $.stages[1].ms_mean: expected a finite number >= 0");
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
  pile2.msMedian = 55.0;
  return {Staged("talus-coloured", 20, 1, 80.0, 80.0,
                 {{"FindContacts", 20.0, 20.0}, {"SolveVelocities", 50.0, 48.0}, {"UpdateSleep", 1.0, 2.0}}),
          Staged("talus-coloured", 20, 2, 50.0, 50.0,
                 {{"FindContacts", 10.0, 10.0}, {"SolveVelocities", 32.0, 30.0}, {"UpdateSleep", 1.0, 1.0}}),
          Pyramid("bullet", 20, 90.0, 0.01), pile1, pile2};
}

TEST(BenchSection, WhereTheTimeGoesGivesEachStageItsMedianShareAndSpeedup) {
  const std::string md = BenchMarkdown(ThreadedRuns());
  const std::size_t heading = md.find(
      "\n### pyramid H = 20: where the time goes\n\n"
      "| stage | talus-coloured | talus-coloured, 2 threads | talus-coloured: speed-up "
      "at 2 threads |\n|---|---|---|---|\n");
  ASSERT_NE(heading, std::string::npos) << md;
  // Shares are stage mean / step mean: 20/80, 48/80, 2/80 and 10/50, 30/50,
  // 1/50; "other" is what the stages leave of the mean (10/80, 9/50); the
  // speed-ups divide the medians (20/10, 50/32, 1/1, 80/50).
  EXPECT_NE(md.find("| FindContacts | 20 (25.0%) | 10 (20.0%) | 2 |\n"
                    "| SolveVelocities | 50 (60.0%) | 32 (60.0%) | 1.56 |\n"
                    "| UpdateSleep | 1 (2.5%) | 1 (2.0%) | 1 |\n"
                    "| other (outside the stages) | (12.5%) | (18.0%) | - |\n"
                    "| step | 80 (100%) | 50 (100%) | 1.6 |\n",
                    heading),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("\n### Where the time goes\n"), std::string::npos) << md;
  EXPECT_NE(md.find("[where the time goes](#where-the-time-goes)"), std::string::npos) << md;
  // Bullet times no stages and the hull pile runs here have none: no column, no table.
  EXPECT_EQ(md.find("hull_pile L = 20: where the time goes"), std::string::npos) << md;
}

TEST(BenchSection, ThreadScalingAndTheTwoThreadGoalCompareRunsOfOneEngine) {
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
  // The main table names the 2-thread run; Bullet's ratio column divides by Bullet.
  EXPECT_NE(md.find("| 20 | 2870 | talus-coloured, 2 threads | 50 | 50 | 0.556 (bullet) |"),
            std::string::npos)
      << md;
  // The scorecard's column is one engine on one thread.
  const std::vector<BenchHeadline> headlines = BenchHeadlines(ThreadedRuns());
  ASSERT_EQ(headlines.size(), 2u);
  EXPECT_EQ(headlines[0].cellByEngine.at("talus-coloured"), "80");
  EXPECT_EQ(headlines[1].cellByEngine.at("talus-coloured"), "100");
}

TEST(BenchSection, OneThreadCountAndNoStagesAddNoStageOrThreadSection) {
  const std::string md = BenchMarkdown({Pyramid("talus", 15, 9.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07)});
  EXPECT_EQ(md.find("where the time goes"), std::string::npos) << md;
  EXPECT_EQ(md.find("Thread scaling"), std::string::npos) << md;
  EXPECT_EQ(md.find("threads ="), std::string::npos) << md;
}

TEST(BenchSection, RatiosDivideByBulletOfTheSameSceneAndParameter) {
  const std::vector<BenchReport> reports = {
      Pyramid("talus", 15, 30.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07), Pyramid("talus", 10, 4.0, 0.001),
      Pyramid("bullet", 10, 8.0, 0.01)};
  const std::string md = BenchMarkdown(reports);
  // Rows by parameter, then engine in first-seen order.
  const std::size_t h10 = md.find("| 10 | 385 | talus | 4 | 4.4 | 0.5 (bullet) |");
  const std::size_t h15 = md.find("| 15 | 1240 | talus | 30 | 33 | 1.5 (bullet) |");
  ASSERT_NE(h10, std::string::npos) << md;
  ASSERT_NE(h15, std::string::npos) << md;
  EXPECT_LT(h10, h15);
  EXPECT_NE(md.find("| 15 | 1240 | bullet | 20 | 22 | 1 (bullet) |"), std::string::npos) << md;
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
  EXPECT_NE(md.find("| 15 | 1240 | talus | 30 | 33 | 2.5 (bullet-f32-tuned) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 10 | 385 | talus | 4 | 4.4 | 0.5 (bullet) |"), std::string::npos) << md;
  EXPECT_NE(md.find("talus / bullet-f32-tuned (the fastest bullet) = 2.5"), std::string::npos) << md;
}

TEST(BenchSection, GoalsSayMetMissedAndWhetherStabilityIsWorse) {
  const std::vector<BenchReport> reports = {
      Pyramid("talus", 15, 9.0, 0.001), Pyramid("bullet", 15, 20.0, 0.07), Pile("talus", 10, 30.0, 0.04, 0),
      Pile("bullet", 10, 40.0, 0.005, 0)};
  const std::string md = BenchMarkdown(reports);
  EXPECT_NE(md.find("- pyramid H = 15: talus / bullet (the fastest bullet) = 0.45 (goal <= 0.5: met); drift "
                    "0.001 m vs 0.07 m "
                    "(no worse)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- hull_pile L = 10: talus / bullet (the fastest bullet) = 0.75 (goal <= 0.5: missed); "
                    "max penetration "
                    "0.04 m vs 0.005 m (worse)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("escaped 0 vs 0 (no worse)"), std::string::npos);
}

TEST(BenchSection, SkippedRunsSayWhyAndLeaveNoGoalWithoutBothEngines) {
  BenchReport skipped = Pyramid("ode-step", 15, 0.0, 0.0);
  skipped.skipped = "too many bodies";
  const std::string md = BenchMarkdown({Pyramid("talus", 15, 9.0, 0.001), skipped});
  EXPECT_NE(md.find("| 15 | 1240 | ode-step | skipped: too many bodies |"), std::string::npos) << md;
  EXPECT_EQ(md.find("### Goals"), std::string::npos);  // no Bullet run to compare with
  EXPECT_NE(md.find("| 15 | 1240 | talus | 9 | 9.9 | - |"), std::string::npos) << md;
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

}  // namespace
}  // namespace talus::harness
