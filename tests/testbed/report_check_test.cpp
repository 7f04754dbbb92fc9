// The results file, the regression check and the report: JSON round trips
// exactly, malformed files are refused at the right place, the check flags
// a doctored result (library and command line, by exit code), and the
// report files are written and well formed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <sys/wait.h>

#include "talus/harness/report/regression_check.h"
#include "talus/harness/report/report.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/talus_backend.h"

#include "support/scratch_files.h"

namespace talus::harness {
namespace report_check_test {

namespace fs = std::filesystem;
// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

const std::string kBoxRest = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json";
const std::string kBoxSlide = std::string(TALUS_SCENARIO_DIR) + "/sliding/box_slide.json";

const BackendRegistry& TalusRegistry() {
  static const BackendRegistry registry = [] {
    BackendRegistry r;
    reference::RegisterTalusBackends(r);
    return r;
  }();
  return registry;
}

// The checkout's runs of the box rest and sliding scenarios.
const std::vector<Run>& SmallRuns() {
  static const std::vector<Run> runs = [] {
    auto loaded = LoadScenarios({kBoxRest, kBoxSlide});
    EXPECT_TRUE(loaded);
    return loaded ? loaded.Value() : std::vector<Run>{};
  }();
  return runs;
}

// A small real results file: Talus on the box rest and sliding scenarios.
const ResultsFile& SmallResults() {
  static const ResultsFile file = [] {
    RunnerOptions options;
    options.backends = {"talus", "talus-writeup"};
    options.deterministic = true;
    auto results = RunAll(TalusRegistry(), SmallRuns(), options);
    EXPECT_TRUE(results);
    return ResultsFile{options.backends, true, results.Value()};
  }();
  return file;
}

// The gate's verdict on one backend of `file` against the small runs; a
// refusal is a failed expectation.
CheckOutcome Recheck(const ResultsFile& file, const std::string& backend) {
  auto outcomes = RecheckResults(file, SmallRuns(), {backend}, TalusRegistry());
  EXPECT_TRUE(outcomes) << outcomes.GetError().message;
  if (!outcomes) {
    CheckOutcome refused;
    refused.problems = {"refused"};
    return refused;
  }
  return outcomes.Value().at(0);
}

// The first checked metric of the first result of `backend`.
MetricResult& FirstChecked(ResultsFile& file, const std::string& backend) {
  for (RunResult& r : file.results) {
    if (r.backend != backend) continue;
    for (MetricResult& m : r.metrics) {
      if (m.checked) return m;
    }
  }
  ADD_FAILURE() << "no checked metric";
  return file.results.at(0).metrics.at(0);
}

// A copy whose first checked Talus metric measured 10% (and 1 cm) off.
ResultsFile Doctored() {
  ResultsFile file = SmallResults();
  for (RunResult& r : file.results) {
    if (r.backend != "talus") continue;
    for (MetricResult& m : r.metrics) {
      if (!m.checked) continue;
      m.measured = m.measured * 1.1 + 0.01;
      Judge(m, m.tolerance);
      return file;
    }
  }
  ADD_FAILURE() << "no checked metric";
  return file;
}

fs::path ScratchDir(const std::string& name) { return testing_support::FreshScratchDir("testbed_" + name); }

// Fields of one CSV line, honouring RFC 4180 quotes.
std::size_t CsvFieldCount(const std::string& line) {
  std::size_t fields = 1;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) ++fields;
  }
  return fields;
}

std::string ReadText(const fs::path& path) { return testing_support::ReadWholeFile(path); }

TEST(ResultsFile, RoundTripsToTheSameBytesWithNaNAsNull) {
  ResultsFile file = SmallResults();
  file.results[0].metrics[0].measured = std::nan("");
  const std::string json = ResultsToJson(file);
  EXPECT_NE(json.find("\"measured\": null"), std::string::npos);
  auto read = ResultsFromJson(json);
  ASSERT_TRUE(read) << read.GetError().message;
  EXPECT_TRUE(std::isnan(read.Value().results[0].metrics[0].measured));
  EXPECT_EQ(ResultsToJson(read.Value()), json);
}

TEST(ResultsFile, MalformedFilesAreRefusedWithThePlace) {
  EXPECT_FALSE(ResultsFromJson("{ not json"));
  auto wrongFormat = ResultsFromJson(R"({"format": "other", "version": 1})");
  ASSERT_FALSE(wrongFormat);
  EXPECT_NE(wrongFormat.GetError().message.find("/format"), std::string::npos);
  nlohmann::json j = nlohmann::json::parse(ResultsToJson(SmallResults()));
  j["results"][1]["metrics"][0].erase("measured");
  auto missing = ResultsFromJson(j.dump());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("/results/1/metrics/0: missing field \"measured\""),
            std::string::npos)
      << missing.GetError().message;
}

TEST(RegressionCheck, PassingResultsPassAndADoctoredMetricIsNamedWithItsNumbers) {
  const CheckOutcome good = Recheck(SmallResults(), "talus");
  EXPECT_TRUE(good.Ok()) << (good.problems.empty() ? "" : good.problems[0]);
  EXPECT_GT(good.checkedMetrics, 6);
  const CheckOutcome bad = Recheck(Doctored(), "talus");
  ASSERT_EQ(bad.problems.size(), 1u);
  EXPECT_EQ(bad.failedMetrics, 1);
  EXPECT_NE(bad.problems[0].find("measured"), std::string::npos);
  EXPECT_NE(bad.problems[0].find("beyond the tolerance"), std::string::npos);
  // The doctored Talus metric does not affect another backend's check.
  EXPECT_TRUE(Recheck(Doctored(), "talus-writeup").Ok());
}

TEST(RegressionCheck, AForgedPassFlagIsRecomputedFromTheMeasuredValue) {
  // Issue 24: a metric measured 42 m off but stored with "pass": true and
  // an error of 0 passed the old check. The verdict comes from the measured
  // value, never from the file's flags.
  ResultsFile forged = SmallResults();
  MetricResult& m = FirstChecked(forged, "talus");
  m.measured += 42.0;
  m.error = 0.0;
  m.pass = true;
  auto reread = ResultsFromJson(ResultsToJson(forged));
  ASSERT_TRUE(reread) << reread.GetError().message;
  const CheckOutcome outcome = Recheck(reread.Value(), "talus");
  ASSERT_EQ(outcome.problems.size(), 1u);
  EXPECT_NE(outcome.problems[0].find("off by 42"), std::string::npos) << outcome.problems[0];
  // Marking it ungated in the file does not take it out of the gate either.
  MetricResult& hidden = FirstChecked(forged, "talus");
  hidden.checked = false;
  hidden.ungated = "says the file";
  EXPECT_FALSE(Recheck(forged, "talus").Ok());
}

TEST(RegressionCheck, AFileThatIsNotTheCheckoutsIsRefusedNamingTheDifference) {
  // A tolerance widened in the file.
  ResultsFile widened = SmallResults();
  FirstChecked(widened, "talus").tolerance.absolute *= 10.0;
  auto refused = RecheckResults(widened, SmallRuns(), {"talus"}, TalusRegistry());
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.GetError().message.find("in the checkout's scenario"), std::string::npos)
      << refused.GetError().message;
  EXPECT_NE(refused.GetError().message.find("tolerance absolute"), std::string::npos)
      << refused.GetError().message;

  // A run of the checkout missing for a gated variant.
  ResultsFile missing = SmallResults();
  std::erase_if(missing.results,
                [](const RunResult& r) { return r.backend == "talus" && r.runId == "box_rest"; });
  auto absent = RecheckResults(missing, SmallRuns(), {"talus", "talus-writeup"}, TalusRegistry());
  ASSERT_FALSE(absent);
  EXPECT_NE(
      absent.GetError().message.find("run box_rest (" + kBoxRest + ") on talus is missing from the file"),
      std::string::npos)
      << absent.GetError().message;

  // A run the checkout does not have (the file's scenario set differs).
  auto extra = RecheckResults(SmallResults(), {SmallRuns().at(0)}, {"talus"}, TalusRegistry());
  ASSERT_FALSE(extra);
  EXPECT_NE(extra.GetError().message.find("which the checkout's scenarios do not have"), std::string::npos)
      << extra.GetError().message;
}

TEST(RegressionCheck, AScenarioWithoutATruthIsRefused) {
  // box_rest with its truth removed: the gate would pass it on 0 metrics.
  std::vector<ScenarioRun> runs = SmallRuns();
  runs.at(0).scenario.truths.clear();
  ResultsFile file = SmallResults();
  for (RunResult& r : file.results) {
    if (r.runId == runs[0].id) std::erase_if(r.metrics, [](const MetricResult& m) { return m.checked; });
  }
  auto refused = RecheckResults(file, runs, {"talus"}, TalusRegistry());
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.GetError().message.find("box_rest (" + kBoxRest + "): the scenario has no truth"),
            std::string::npos)
      << refused.GetError().message;
}

TEST(RegressionCheck, EveryRecomputedVerdictMatchesTheRunnersOnARealRun) {
  // The recomputation (RecomputedPass, ExpectedMetrics) and the evaluators
  // must agree on every metric of an honest file, the tipping threshold
  // test included, or the gate would judge by other rules than the report.
  auto runs = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/sliding/tall_box_tipping.json", kBoxSlide,
                             std::string(TALUS_SCENARIO_DIR) + "/tumbling/box_toss.json"});
  ASSERT_TRUE(runs) << runs.GetError().message;
  RunnerOptions options;
  options.backends = {"talus", "talus-writeup"};
  options.deterministic = true;
  auto results = RunAll(TalusRegistry(), runs.Value(), options);
  ASSERT_TRUE(results);
  int compared = 0;
  for (const RunResult& r : results.Value()) {
    const auto run = std::find_if(runs.Value().begin(), runs.Value().end(),
                                  [&](const ScenarioRun& candidate) { return candidate.id == r.runId; });
    ASSERT_NE(run, runs.Value().end());
    const std::vector<ExpectedMetric> expected = ExpectedMetrics(*run, r.backend);
    ASSERT_LE(expected.size(), r.metrics.size()) << r.runId;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const MetricResult& m = r.metrics[i];
      EXPECT_EQ(m.name, expected[i].name) << r.runId;
      EXPECT_EQ(m.tolerance, expected[i].tolerance) << r.runId << " " << m.name;
      EXPECT_EQ(m.checked, expected[i].checked) << r.runId << " " << m.name;
      EXPECT_EQ(RecomputedPass(m, expected[i].tolerance), m.pass)
          << r.runId << " " << r.backend << " " << m.name;
      ++compared;
    }
  }
  EXPECT_GT(compared, 20);
}

TEST(RegressionCheck, AFailedRunIsAProblem) {
  ResultsFile file = SmallResults();
  file.results[0].error = "talus: body \"box\": bad hull";
  file.results[0].metrics.clear();
  const CheckOutcome failed = Recheck(file, "talus");
  ASSERT_FALSE(failed.Ok());
  EXPECT_NE(failed.problems[0].find("the run failed"), std::string::npos);
}

TEST(Report, FilesAreWrittenAndWellFormed) {
  const fs::path dir = ScratchDir("report");
  const fs::path chart = dir / "fake_chart.js";
  std::ofstream(chart) << "window.Chart = function() {}; // </script> must not end the element\n";
  auto written = WriteReport(SmallResults(), dir / "out", chart);
  ASSERT_TRUE(written) << written.GetError().message;

  // JSON: parses back to the same results.
  auto json = ReadResultsFile(dir / "out" / "results.json");
  ASSERT_TRUE(json) << json.GetError().message;
  EXPECT_EQ(json.Value().results.size(), SmallResults().results.size());

  // CSV: a header and one row per metric, every row with the header's field count.
  std::istringstream csv(ReadText(dir / "out" / "results.csv"));
  std::string line;
  std::size_t rows = 0;
  std::getline(csv, line);
  const std::size_t fields = CsvFieldCount(line);
  std::size_t metrics = 0;
  for (const RunResult& r : SmallResults().results) metrics += r.metrics.size();
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(CsvFieldCount(line), fields) << line;
  }
  EXPECT_EQ(rows, metrics);

  // Markdown: every run has a section, with the settings at the end.
  const std::string summary = ReadText(dir / "out" / "summary.md");
  for (const RunResult& r : SmallResults().results) {
    EXPECT_NE(summary.find("## " + r.runId + "\n"), std::string::npos) << r.runId;
  }
  EXPECT_NE(summary.find("### talus-writeup"), std::string::npos);

  // HTML: one document, the library inlined without its closing tag, no
  // external resource but its data file beside it, whose plot data parses.
  const std::string html = ReadText(dir / "out" / "report.html");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("window.Chart = function"), std::string::npos);
  EXPECT_EQ(html.find("// </script>"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_NE(html.find("<script src=\"report-data.js\"></script>"), std::string::npos);
  const std::string script = ReadText(dir / "out" / "report-data.js");
  const std::string open = "window.talusReportData = ";
  const auto start = script.find(open);
  ASSERT_NE(start, std::string::npos);
  ASSERT_EQ(script.substr(script.size() - 2), ";\n");
  const std::string data = script.substr(start + open.size(), script.size() - 2 - start - open.size());
  const auto parsed = nlohmann::json::parse(data, nullptr, false);
  ASSERT_FALSE(parsed.is_discarded());
  EXPECT_EQ(parsed["plots"]["runs"].size(), 7u);  // box_rest and the 6 box_slide runs
  EXPECT_FALSE(parsed.contains("replays"));       // in their own file
  EXPECT_NE(html.find("<script src=\"report-replay.js\"></script>"), std::string::npos);
  EXPECT_EQ(ReadText(dir / "out" / "report-replay.js"),
            "// The replays of report.html (talus-testbed report), loaded by the page.\n"
            "window.talusReportReplays = [];\n");  // none recorded
  // Missing charting library: a clear error naming the file.
  auto missing = WriteReport(SmallResults(), dir / "out2", dir / "missing.js");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("missing.js"), std::string::npos);
}

#ifdef TALUS_TESTBED_BINARY
int Shell(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(TestbedCommand, CheckExitsNonZeroOnARegressionAndZeroWhenPassing) {
  const fs::path dir = ScratchDir("check");
  ASSERT_TRUE(WriteResultsFile(dir / "good.json", SmallResults()));
  ASSERT_TRUE(WriteResultsFile(dir / "bad.json", Doctored()));
  const std::string binary = TALUS_TESTBED_BINARY;
  const std::string scenarios = " " + kBoxRest + " " + kBoxSlide;
  EXPECT_EQ(Shell(binary + " check --results " + (dir / "good.json").string() + scenarios), 0);
  EXPECT_EQ(Shell(binary + " check --results " + (dir / "bad.json").string() + scenarios), 1);
  EXPECT_EQ(Shell(binary + " check --results " + (dir / "none.json").string() + scenarios), 2);
  // No bullet results in the file: refused as missing runs.
  EXPECT_EQ(Shell(binary + " check --backend bullet --results " + (dir / "good.json").string() + scenarios),
            2);
  // Against the whole suite (the default) the two-scenario file is refused.
  EXPECT_EQ(Shell(binary + " check --results " + (dir / "good.json").string() + " " + TALUS_SCENARIO_DIR), 2);
}

TEST(TestbedCommand, RunWritesDeterministicResultsAndRefusesBadArguments) {
  const fs::path dir = ScratchDir("run");
  const std::string binary = TALUS_TESTBED_BINARY;
  const std::string scenario = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json";
  const std::string common = " run " + scenario + " -q --deterministic -b talus,ode-step -o ";
  ASSERT_EQ(Shell(binary + common + (dir / "a").string() + " -j 1"), 0);
  ASSERT_EQ(Shell(binary + common + (dir / "b").string() + " -j 3"), 0);
  EXPECT_EQ(ReadText(dir / "a" / "results.json"), ReadText(dir / "b" / "results.json"));
  EXPECT_EQ(ReadText(dir / "a" / "results.trajectories.json"),
            ReadText(dir / "b" / "results.trajectories.json"));
  EXPECT_EQ(ReadText(dir / "a" / "results.replays.json"), ReadText(dir / "b" / "results.replays.json"));
  EXPECT_EQ(Shell(binary + " run " + scenario + " -q -b havok -o " + (dir / "c").string()), 2);
  EXPECT_EQ(Shell(binary + " run /nonexistent.json -q -o " + (dir / "c").string()), 2);
  EXPECT_EQ(Shell(binary + " run --jobs -3"), 2);
  EXPECT_EQ(Shell(binary + " frobnicate"), 2);
  const fs::path chart = dir / "chart.js";
  std::ofstream(chart) << "window.Chart = function() {};\n";
  EXPECT_EQ(
      Shell(binary + " report " + (dir / "a" / "results.json").string() + " --chart-js " + chart.string()),
      0);
  EXPECT_TRUE(fs::exists(dir / "a" / "report.html"));
}
#endif

}  // namespace report_check_test
}  // namespace talus::harness
