// results.json (version 2) writes each backend's settings and each run's
// metric definitions once, in two tables at its top (run/results_tables.h),
// and the results name them by index. Written and read back, every result
// has exactly the settings and metrics it had, however they vary between a
// backend's runs and a run's backends; each long text is in the file once;
// a reference that names nothing, and a file of version 1, are refused
// naming the place, the file and the version expected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "support/scratch_files.h"
#include "talus/harness/run/results_file.h"

namespace talus::harness {
namespace results_tables_test {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kSlideReason =
    "the slide's stopping distance to a tenth of the sliding friction's step error";
const char* const kIterationsEffect = "twenty iterations: the stack settles within the step budget";

Setting Departure(const char* key, const char* value, const char* engineDefault, const char* effect) {
  Setting s{key, value};
  s.engineDefault = engineDefault;
  s.effect = effect;
  return s;
}

MetricResult Metric(const char* name, double measured, double absolute, const char* reason) {
  MetricResult m = MakeMetric(name, "m");
  m.measured = measured;
  m.truth = 0.25;
  m.truthIntegrator = 0.2499;
  m.error = measured - m.truthIntegrator;
  m.tolerance.absolute = absolute;
  m.reason = reason;
  m.checked = true;
  m.pass = std::abs(m.error) <= absolute;
  return m;
}

// Two runs through two backends. What the tables must keep apart: Talus's
// iterations differ between the runs (two settings lists of one backend),
// Bullet's list is longer in the second run and in another order; Bullet's
// slide metric is ungated (the ungated note is the result's, not the
// definition's); the second run repeats a metric name with another
// tolerance (two definitions of one name, told apart by index); a published
// figure without an upper end and an unmeasured value (NaN) travel too.
ResultsFile VaryingResults() {
  ResultsFile file;
  file.backends = {"talus", "bullet"};
  file.deterministic = true;
  for (const char* run : {"box_slide[mu=0.3]", "box_slide[mu=0.5]"}) {
    const bool second = std::strcmp(run, "box_slide[mu=0.5]") == 0;
    for (const char* backend : {"talus", "bullet"}) {
      RunResult r;
      r.scenario = "box_slide";
      r.file = "scenarios/friction/box_slide.json";
      r.runId = run;
      r.backend = backend;
      r.sweepValues = {{"mu", second ? "0.5" : "0.3"}};
      r.timeStep = 0.01;
      r.steps = 100;
      r.bodyNames = {"ground", "box"};
      if (std::strcmp(backend, "talus") == 0) {
        r.settings = {Setting{"time step (s)", "0.01"},
                      second ? Departure("velocity iterations", "20", "10", kIterationsEffect)
                             : Setting{"velocity iterations", "10 (engine default)"}};
      } else {
        r.settings = {Setting{"time step (s)", "0.01"}, Setting{"solver iterations", "10"}};
        if (second) r.settings.insert(r.settings.begin(), Setting{"explicit contact pairs", "1"});
      }
      r.metrics.push_back(Metric("sliding_stop.distance", second ? 0.2 : 0.24, 0.005, kSlideReason));
      if (std::strcmp(backend, "bullet") == 0) {
        r.metrics.back().checked = false;
        r.metrics.back().ungated = "Bullet's friction anchors drift";
      }
      MetricResult penetration = Metric("penetration.max", second ? kNaN : 0.001, 0.004, "about the slop");
      if (second) {
        penetration.publishedValue = 0.002;
        penetration.publishedUpper = kNaN;
        penetration.publishedSource = "a measured figure";
        r.metrics.push_back(Metric("penetration.max", 0.003, 0.01, "a second bound on the same depth"));
      }
      r.metrics.push_back(penetration);
      file.results.push_back(r);
    }
  }
  return file;
}

// Equal, NaN equal to NaN.
void ExpectSameNumber(double a, double b, const std::string& what) {
  if (std::isnan(a) || std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what << ": " << a << " against " << b;
  } else {
    EXPECT_EQ(a, b) << what;
  }
}

void ExpectSameResults(const ResultsFile& read, const ResultsFile& written) {
  ASSERT_EQ(read.results.size(), written.results.size());
  for (std::size_t i = 0; i < written.results.size(); ++i) {
    const RunResult& a = read.results[i];
    const RunResult& b = written.results[i];
    const std::string at = "result " + std::to_string(i);
    EXPECT_EQ(a.runId, b.runId) << at;
    EXPECT_EQ(a.backend, b.backend) << at;
    ASSERT_EQ(a.settings.size(), b.settings.size()) << at;
    for (std::size_t k = 0; k < b.settings.size(); ++k) {
      EXPECT_EQ(a.settings[k].key, b.settings[k].key) << at;
      EXPECT_EQ(a.settings[k].value, b.settings[k].value) << at;
      EXPECT_EQ(a.settings[k].engineDefault, b.settings[k].engineDefault) << at;
      EXPECT_EQ(a.settings[k].effect, b.settings[k].effect) << at;
    }
    ASSERT_EQ(a.metrics.size(), b.metrics.size()) << at;
    for (std::size_t k = 0; k < b.metrics.size(); ++k) {
      const MetricResult& m = a.metrics[k];
      const MetricResult& n = b.metrics[k];
      const std::string place = at + " metric " + std::to_string(k);
      EXPECT_EQ(m.name, n.name) << place;
      EXPECT_EQ(m.unit, n.unit) << place;
      ExpectSameNumber(m.measured, n.measured, place + " measured");
      ExpectSameNumber(m.truth, n.truth, place + " truth");
      ExpectSameNumber(m.truthIntegrator, n.truthIntegrator, place + " truthIntegrator");
      ExpectSameNumber(m.error, n.error, place + " error");
      ExpectSameNumber(m.tolerance.absolute, n.tolerance.absolute, place + " absolute");
      ExpectSameNumber(m.tolerance.relative, n.tolerance.relative, place + " relative");
      EXPECT_EQ(m.reason, n.reason) << place;
      EXPECT_EQ(m.checked, n.checked) << place;
      EXPECT_EQ(m.pass, n.pass) << place;
      EXPECT_EQ(m.ungated, n.ungated) << place;
      ExpectSameNumber(m.publishedValue, n.publishedValue, place + " published value");
      ExpectSameNumber(m.publishedUpper, n.publishedUpper, place + " published upper");
      EXPECT_EQ(m.publishedSource, n.publishedSource) << place;
    }
  }
}

// How many times `needle` occurs in `text`.
std::size_t Occurrences(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

std::string Refusal(const Json& j) {
  auto read = ResultsFromJson(j.dump());
  EXPECT_FALSE(read) << "read a malformed file";
  return read ? "" : read.GetError().message;
}

TEST(ResultsTables, EveryResultReadsBackWithTheSettingsAndMetricsItWasWrittenWith) {
  const ResultsFile written = VaryingResults();
  // The one-text form (shard files) and the three files on disk.
  const std::string text = ResultsToJson(written);
  auto fromText = ResultsFromJson(text);
  ASSERT_TRUE(fromText) << fromText.GetError().message;
  ExpectSameResults(fromText.Value(), written);
  EXPECT_EQ(ResultsToJson(fromText.Value()), text);

  const fs::path dir = testing_support::FreshScratchDir("results_tables_round_trip");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", written));
  auto fromFiles = ReadResultsFile(dir / "results.json");
  ASSERT_TRUE(fromFiles) << fromFiles.GetError().message;
  ExpectSameResults(fromFiles.Value(), written);
}

TEST(ResultsTables, EachBackendsSettingsAndEachRunsDefinitionsAreWrittenOnce) {
  const std::string text = ResultsToJson(VaryingResults());
  // Two results of each run carry the slide's reason; two runs of Talus
  // carry the time step; one result carries the iterations' departure.
  EXPECT_EQ(Occurrences(text, kSlideReason), 2u);  // once per run: one definition each
  EXPECT_EQ(Occurrences(text, kIterationsEffect), 1u);
  const Json j = Json::parse(text);
  EXPECT_EQ(j["version"], 2);
  // Talus: 3 distinct settings in 2 lists; Bullet: 3 in 2 lists.
  EXPECT_EQ(j["settings"]["talus"]["entries"].size(), 3u);
  EXPECT_EQ(j["settings"]["talus"]["lists"], Json::parse("[[0, 1], [0, 2]]"));
  EXPECT_EQ(j["settings"]["bullet"]["lists"], Json::parse("[[0, 1], [2, 0, 1]]"));
  // The second run: the slide, the repeated name's two tolerances.
  EXPECT_EQ(j["metricDefinitions"]["box_slide[mu=0.5]"].size(), 3u);
  EXPECT_EQ(j["results"][3]["settings"], 1);
  EXPECT_EQ(j["results"][3]["metrics"][2]["definition"], 2);
  EXPECT_FALSE(j["results"][3]["metrics"][0].contains("tolerance"));
}

TEST(ResultsTables, AFileOfVersionOneIsRefusedNamingTheFileAndTheVersionExpected) {
  Json j = Json::parse(ResultsToJson(VaryingResults()));
  j["version"] = 1;
  EXPECT_EQ(Refusal(j), "/version: 1, expected 2 (an older build's file: run it again with this build)");

  const fs::path dir = testing_support::FreshScratchDir("results_tables_version");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", VaryingResults()));
  j = Json::parse(testing_support::ReadWholeFile(dir / "results.json"));
  j["version"] = 1;
  std::ofstream(dir / "results.json") << j.dump(2) << "\n";
  auto read = ReadResultsFile(dir / "results.json");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.GetError().message,
            (dir / "results.json").string() +
                ": /version: 1, expected 2 (an older build's file: run it again with "
                "this build)");
}

TEST(ResultsTables, AReferenceToNothingIsRefusedWithThePlace) {
  const Json good = Json::parse(ResultsToJson(VaryingResults()));
  Json j = good;
  j["results"][1]["settings"] = 2;
  EXPECT_EQ(Refusal(j), "/results/1/settings: 2 is not an index of the 2 settings lists of \"bullet\"");
  j = good;
  j["results"][0]["settings"] = "0";
  EXPECT_EQ(Refusal(j), "/results/0/settings: expected an integer index");
  j = good;
  j["settings"].erase("talus");
  EXPECT_EQ(Refusal(j), "/results/0/settings: backend \"talus\" has no table in /settings");
  j = good;
  j["settings"]["talus"]["lists"][1][1] = 3;
  EXPECT_EQ(Refusal(j), "/settings/talus/lists/1/1: 3 is not an index of the 3 entries of this backend");
  j = good;
  j["results"][2]["metrics"][1]["definition"] = -1;
  EXPECT_EQ(Refusal(j),
            "/results/2/metrics/1/definition: -1 is not an index of the 3 metric definitions of "
            "\"box_slide[mu=0.5]\"");
  j = good;
  j["metricDefinitions"].erase("box_slide[mu=0.3]");
  EXPECT_EQ(Refusal(j),
            "/results/0/metrics/0/definition: run \"box_slide[mu=0.3]\" has no list in /metricDefinitions");
  j = good;
  j["results"][0]["metrics"][0].erase("definition");
  EXPECT_EQ(Refusal(j), "/results/0/metrics/0: missing field \"definition\"");
  j = good;
  j["metricDefinitions"]["box_slide[mu=0.3]"][0]["tolerance"].erase("reason");
  EXPECT_EQ(Refusal(j), "/metricDefinitions/box_slide[mu=0.3]/0/tolerance: missing field \"reason\"");
  j = good;
  j.erase("settings");
  EXPECT_EQ(Refusal(j), ": missing field \"settings\"");
}

}  // namespace results_tables_test
}  // namespace talus::harness
