// The large-scenes section of the report: talus-scenes's JSON lines read
// back exactly (round trip), malformed lines refused with the line and the
// key, the tables' ratios against Bullet, the goal verdicts (met, missed,
// worse) and the section in summary.md and report.html only when given.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

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
