// The stability envelope as a report section: stress.json written by
// StressJson and read back by ParseStressJson without loss (NaN limits
// included), malformed files refused with the JSON path, and the section
// in summary.md and report.html only when given.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "talus/harness/report/report.h"
#include "talus/harness/stress/stress.h"

namespace talus::harness {
namespace stress_section_test {

std::vector<StressEntry> Entries() {
  StressEntry column{.axis = "column", .backend = "talus", .envelope = {}};
  column.envelope.lastPass = 24;
  column.envelope.firstFail = 25;
  column.envelope.probes = {{.value = 24, .pass = true, .measure = 0.001, .detail = ""},
                            {.value = 25, .pass = false, .measure = 0.31, .detail = "top box moved 0.31 m"}};
  StressEntry speed{.axis = "speed", .backend = "bullet", .envelope = {}};
  speed.envelope.lastPass = 1.0 / 3.0;  // firstFail stays NaN: every probe passed
  speed.envelope.probes = {
      {.value = 1.0 / 3.0, .pass = true, .measure = std::numeric_limits<double>::quiet_NaN(), .detail = ""}};
  return {column, speed};
}

TEST(StressJson, EnvelopesSurviveTheRoundTripExactly) {
  const std::vector<StressEntry> written = Entries();
  auto read = ParseStressJson(StressJson(written), "stress.json");
  ASSERT_TRUE(read) << read.GetError().message;
  ASSERT_EQ(read.Value().size(), 2u);
  const StressEntry& column = read.Value()[0];
  EXPECT_EQ(column.axis, "column");
  EXPECT_EQ(column.envelope.lastPass, 24);
  EXPECT_EQ(column.envelope.firstFail, 25);
  ASSERT_EQ(column.envelope.probes.size(), 2u);
  EXPECT_EQ(column.envelope.probes[1].detail, "top box moved 0.31 m");
  EXPECT_FALSE(column.envelope.probes[1].pass);
  const StressEntry& speed = read.Value()[1];
  EXPECT_EQ(speed.envelope.lastPass, 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(speed.envelope.firstFail));
  EXPECT_TRUE(std::isnan(speed.envelope.probes[0].measure));
  // Reading what was written and writing it again gives the same text.
  EXPECT_EQ(StressJson(read.Value()), StressJson(written));
}

TEST(StressJson, MalformedFilesAreRefusedWithThePath) {
  const auto message = [](const std::string& text) {
    auto read = ParseStressJson(text, "s.json");
    return read ? std::string("accepted") : read.GetError().message;
  };
  EXPECT_EQ(message("["), "s.json: not valid JSON");
  EXPECT_EQ(message(R"({"format":"other","version":1,"envelopes":[]})"),
            "s.json: $.format: expected \"talus-testbed-stress\"");
  EXPECT_EQ(message(R"({"format":"talus-testbed-stress","version":2,"envelopes":[]})"),
            "s.json: $.version: expected 1");
  EXPECT_EQ(message(R"({"format":"talus-testbed-stress","version":1,"envelopes":[{"axis":"column",)"
                    R"("backend":"talus","lastPass":1,"firstFail":null,"probes":[{"value":1,"pass":"yes",)"
                    R"("measure":null,"detail":""}]}]})"),
            "s.json: $.envelopes[0].probes[0].pass: expected true or false");
  auto missing = ReadStressFile("/nonexistent/stress.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("/nonexistent/stress.json"), std::string::npos);
}

TEST(StressSection, ReportHasTheEnvelopeOnlyWhenGiven) {
  const std::vector<StressEntry> entries = Entries();
  const ResultsFile file;
  const std::string table = StressMarkdown(entries);
  const std::string firstLine = table.substr(0, table.find('\n'));
  EXPECT_EQ(SummaryMarkdown(file).find(firstLine), std::string::npos);
  EXPECT_NE(SummaryMarkdown(file, {.stress = &entries}).find(table), std::string::npos);
  const std::string html = ReportHtml(file, "", "", {.stress = &entries});
  EXPECT_NE(html.find("top box moved 0.31 m"), std::string::npos);
  EXPECT_EQ(ReportHtml(file, "").find("top box moved 0.31 m"), std::string::npos);
}

}  // namespace stress_section_test
}  // namespace talus::harness
