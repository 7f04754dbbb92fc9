// The report's opening scorecard (report_scorecard.h) on small synthetic
// results whose counts are worked out by hand below: rows per engine and
// configuration, the sweep and large-scene columns only when those extras
// are given, and every FAIL linked to its run's section.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "report/report_scorecard.h"
#include "support/synthetic_results.h"
#include "talus/harness/report/report.h"
#include "talus/harness/run/results_file.h"

namespace talus::harness {
namespace scorecard_section_test {

// A truth with a 0.01 m tolerance; `gate` false makes it ungated (still judged).
MetricResult Metric(const std::string& name, double error, bool gate = true) {
  return testing_support::SyntheticTruth(name, error, gate);
}

// A measured figure with no tolerance: never judged.
MetricResult Figure(const std::string& name) {
  MetricResult m;
  m.name = name;
  m.measured = 3.0;
  return m;
}

RunResult MakeRun(const std::string& runId, const std::string& backend, std::vector<MetricResult> metrics,
                  const std::string& error = "") {
  return testing_support::SyntheticRun(runId, backend, std::move(metrics), 0.01, error);
}

// Two runs, three configurations:
//   box[mu=0.3]: talus a ok, b ok; ode-step a FAIL, b ok; ode-step-tuned a ok, b FAIL
//   col_5:       talus a FAIL (ungated), b ok, drift (no tolerance);
//                ode-step stopped; ode-step-tuned a ok, b ok
// By hand: talus 3 of 4 judged, 1 of 2 runs fully passing, FAIL in col_5;
// ode-step 1 of 2 judged (its stopped run judges nothing), 0 of 2 runs, 1
// stopped, its one FAIL (a) removed by ode-step-tuned, so setting-caused;
// ode-step-tuned 3 of 4, 1 of 2 runs, its FAIL (b) its own.
ResultsFile Results() {
  ResultsFile file;
  file.backends = {"talus", "ode-step", "ode-step-tuned"};
  file.results = {
      MakeRun("box[mu=0.3]", "talus", {Metric("a", 0.001), Metric("b", -0.002)}),
      MakeRun("box[mu=0.3]", "ode-step", {Metric("a", 0.2), Metric("b", 0.0)}),
      MakeRun("box[mu=0.3]", "ode-step-tuned", {Metric("a", 0.003), Metric("b", 0.05)}),
      MakeRun("col_5", "talus", {Metric("a", 4.5, false), Metric("b", 0.0), Figure("drift")}),
      MakeRun("col_5", "ode-step", {}, "LCP internal error"),
      MakeRun("col_5", "ode-step-tuned", {Metric("a", 0.0), Metric("b", 0.0)}),
  };
  return file;
}

const ScorecardRow* FindRow(const Scorecard& card, const std::string& backend) {
  for (const ScorecardRow& row : card.rows) {
    if (row.backend == backend) return &row;
  }
  return nullptr;
}

TEST(ScorecardSection, HeadingAnchorsFollowGitHub) {
  EXPECT_EQ(HeadingAnchor("box[mu=0.3]"), "boxmu03");
  EXPECT_EQ(HeadingAnchor("Run time against error"), "run-time-against-error");
  EXPECT_EQ(HeadingAnchor("box_column_5"), "box_column_5");
}

TEST(ScorecardSection, CountsMatchTheHandCount) {
  const Scorecard card = BuildScorecard(Results(), {});
  ASSERT_EQ(card.rows.size(), 3u);
  EXPECT_EQ(card.rows[0].backend, "talus");
  const ScorecardRow* talus = FindRow(card, "talus");
  const ScorecardRow* ode = FindRow(card, "ode-step");
  const ScorecardRow* tuned = FindRow(card, "ode-step-tuned");
  ASSERT_TRUE(talus && ode && tuned);
  EXPECT_EQ(talus->judged, 4);
  EXPECT_EQ(talus->passed, 3);
  EXPECT_EQ(talus->runs, 2);
  EXPECT_EQ(talus->runsPassing, 1);
  EXPECT_EQ(talus->runsStopped, 0);
  EXPECT_EQ(talus->settingFails, 0);
  EXPECT_EQ(ode->judged, 2);
  EXPECT_EQ(ode->passed, 1);
  EXPECT_EQ(ode->runsPassing, 0);
  EXPECT_EQ(ode->runsStopped, 1);
  EXPECT_EQ(ode->settingFails, 1);
  EXPECT_EQ(tuned->judged, 4);
  EXPECT_EQ(tuned->passed, 3);
  EXPECT_EQ(tuned->runsPassing, 1);
  EXPECT_EQ(tuned->settingFails, 0);
  EXPECT_FALSE(card.hasSweep);
  EXPECT_TRUE(card.scenes.empty());
}

TEST(ScorecardSection, OpensTheSummaryWithLinkedRowsAndNoExtraColumns) {
  const std::string md = SummaryMarkdown(Results());
  const auto scorecard = md.find("## Scorecard");
  ASSERT_NE(scorecard, std::string::npos) << md;
  EXPECT_LT(scorecard, md.find("## Overview"));
  EXPECT_NE(md.find("| talus | 3 of 4 (75%) | 1 of 2 | 0 | 0 | [col_5](#col_5) (1) |"), std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| ode-step | 1 of 2 (50%) | 0 of 2 | 1 | 1 | [box[mu=0.3]](#boxmu03) (1), [col_5](#col_5) "
              "(stopped) |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| ode-step-tuned | 3 of 4 (75%) | 1 of 2 | 0 | 0 | [box[mu=0.3]](#boxmu03) (1) |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("most accurate at equal cost"), std::string::npos) << md;
  EXPECT_EQ(md.find("ms/step"), std::string::npos) << md;
  // The long table stays, its FAILs linked to the sections, which name the causes.
  EXPECT_NE(md.find("| box[mu=0.3] | a (m) | 1 | +0.001 ok | +0.2 [FAIL](#boxmu03) | +0.003 ok |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("+4.5 [FAIL (ungated)](#col_5)"), std::string::npos) << md;
  EXPECT_NE(md.find("\n## box[mu=0.3]\n"), std::string::npos) << md;
  EXPECT_NE(md.find("- `ode-step` FAILs a (0.2): a setting: removed by `ode-step-tuned` (0.003)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- `talus` FAILs a (ungated) (4.5): the engine's own behaviour"), std::string::npos)
      << md;
}

TEST(ScorecardSection, HtmlLinksEveryFailToAnAnchorThatExists) {
  const std::string html = ReportHtml(Results(), "/* chart */");
  EXPECT_NE(html.find("<h2 id=\"boxmu03\">box[mu=0.3]</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"col_5\">col_5</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"fail\">+0.2 <a href=\"#boxmu03\">FAIL</a></td>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#boxmu03\">box[mu=0.3]</a> (1)"), std::string::npos);
  // Every link's target is on the page.
  for (std::size_t at = html.find("href=\"#"); at != std::string::npos; at = html.find("href=\"#", at + 1)) {
    const std::size_t start = at + 7;
    const std::string anchor = html.substr(start, html.find('"', start) - start);
    EXPECT_NE(html.find("id=\"" + anchor + "\""), std::string::npos) << anchor;
  }
  // The chart: pass fractions 3/4, 1/2, 3/4, before the overview.
  const auto chart = html.find("id=\"scorecard-data\">");
  ASSERT_NE(chart, std::string::npos);
  EXPECT_LT(chart, html.find("<h2 id=\"overview\">"));
  EXPECT_NE(html.find("\"fractions\":[0.75,0.5,0.75]"), std::string::npos) << html.substr(chart, 200);
}

TEST(ScorecardSection, RepeatedAnchorsAreNumberedAlikeInBothFiles) {
  // "box[v0=1.5]" and "box[v0=15]" share the anchor "boxv015": the second
  // section is "boxv015-1", as GitHub numbers it.
  ResultsFile file;
  file.backends = {"talus"};
  file.results = {MakeRun("box[v0=1.5]", "talus", {Metric("a", 0.5)}),
                  MakeRun("box[v0=15]", "talus", {Metric("a", 0.5)})};
  const std::map<std::string, std::string> anchors = RunAnchors(file);
  EXPECT_EQ(anchors.at("box[v0=1.5]"), "boxv015");
  EXPECT_EQ(anchors.at("box[v0=15]"), "boxv015-1");
  const std::string md = SummaryMarkdown(file);
  EXPECT_NE(md.find("[box[v0=15]](#boxv015-1) (1)"), std::string::npos) << md;
  EXPECT_NE(md.find("| box[v0=15] | a (m) | 1 | +0.5 [FAIL](#boxv015-1) |"), std::string::npos) << md;
  const std::string html = ReportHtml(file, "/* chart */");
  EXPECT_NE(html.find("<h2 id=\"boxv015-1\">box[v0=15]</h2>"), std::string::npos);
}

TEST(ScorecardSection, SweepAndScenesAddTheirColumns) {
  // The sweep: three scenarios, talus and bullet at equal cost (1 s each);
  // error scalars |error| / 0.01: g1 talus 0.1 vs 0.5 (talus wins), g2 0.9
  // vs 0.2 (bullet wins), g3 0.3 vs 0.3 (tie, no winner). So talus 1 of 3,
  // bullet 1 of 3.
  ResultsFile sweep;
  sweep.backends = {"talus", "bullet"};
  sweep.results = {
      MakeRun("g1", "talus", {Metric("a", 0.001)}), MakeRun("g1", "bullet", {Metric("a", 0.005)}),
      MakeRun("g2", "talus", {Metric("a", 0.009)}), MakeRun("g2", "bullet", {Metric("a", 0.002)}),
      MakeRun("g3", "talus", {Metric("a", 0.003)}), MakeRun("g3", "bullet", {Metric("a", 0.003)})};
  // The scenes: pyramid at H = 10 and the reference H = 15 (ode-step skipped there).
  std::vector<BenchReport> scenes;
  for (const auto& [engine, parameter, ms] : {std::tuple<const char*, int, double>{"talus", 10, 1.0},
                                              {"talus", 15, 2.5},
                                              {"ode-step", 10, 4.0},
                                              {"bullet-f32", 15, 3.25}}) {
    BenchReport r;
    r.engine = engine;
    r.scene = "pyramid";
    r.parameter = parameter;
    r.steps = 600;
    r.totalMs = 600.0 * ms;
    r.msMean = ms;
    r.msMax = ms;
    scenes.push_back(r);
  }
  BenchReport skipped;
  skipped.engine = "ode-step";
  skipped.scene = "pyramid";
  skipped.parameter = 15;
  skipped.skipped = "too many bodies";
  scenes.push_back(skipped);
  ReportExtras extras;
  extras.sweep = &sweep;
  extras.scenes = &scenes;

  const Scorecard card = BuildScorecard(Results(), extras);
  ASSERT_EQ(card.scenes, std::vector<std::string>{"pyramid H = 15 (mean ms/step)"});
  // Engines only the extras ran get rows of their own, after the results' ones.
  ASSERT_EQ(card.rows.size(), 5u);
  EXPECT_EQ(card.rows[3].backend, "bullet");
  EXPECT_EQ(card.rows[4].backend, "bullet-f32");
  const std::string md = ScorecardMarkdown(card);
  EXPECT_NE(md.find("| most accurate at equal cost | pyramid H = 15 (mean ms/step) |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| talus | 3 of 4 (75%) | 1 of 2 | 0 | 0 | 1 of 3 | 2.5 | [col_5](#col_5) (1) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| ode-step | 1 of 2 (50%) | 0 of 2 | 1 | 1 | - | skipped |"), std::string::npos) << md;
  EXPECT_NE(md.find("| ode-step-tuned | 3 of 4 (75%) | 1 of 2 | 0 | 0 | - | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bullet | - | - | - | - | 1 of 3 | - | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bullet-f32 | - | - | - | - | - | 3.25 | - |"), std::string::npos) << md;
}

}  // namespace scorecard_section_test
}  // namespace talus::harness
