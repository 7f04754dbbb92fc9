// The SAT validation section of the report: talus-sat-check's JSON read by
// the harness (tests/data/sat_check/small.json is the program's own output
// for 12 pairs, seed 1, with the per-pair records dropped), the section in
// summary.md and report.html, and malformed files refused with the place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "talus/harness/report/report.h"
#include "talus/harness/report/sat_check_results.h"

namespace talus::harness {
namespace sat_check_section_test {

const std::filesystem::path kFixture =
    std::filesystem::path(TALUS_TEST_DATA_DIR) / "sat_check" / "small.json";

nlohmann::json FixtureJson() {
  std::ifstream in(kFixture);
  EXPECT_TRUE(in) << kFixture;
  return nlohmann::json::parse(in);
}

SatCheckSummary Fixture() {
  auto read = ReadSatCheckFile(kFixture);
  EXPECT_TRUE(read) << read.GetError().message;
  return read ? read.Value() : SatCheckSummary{};
}

std::size_t Occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SatCheckSection, FixtureIsReadWithEveryMethodInFileOrder) {
  const nlohmann::json json = FixtureJson();
  const SatCheckSummary s = Fixture();
  EXPECT_EQ(s.pairCount, json["pairCount"].get<int>());
  EXPECT_EQ(s.seed, 1);
  ASSERT_EQ(s.methods.size(), json["methods"].size());
  for (std::size_t i = 0; i < s.methods.size(); ++i) {
    const nlohmann::json& m = json["methods"][i];
    EXPECT_EQ(s.methods[i].name, m["name"].get<std::string>());
    EXPECT_EQ(s.methods[i].agree, m["verdict"]["agree"].get<int>());
    // Exact: the reader copies the double it parsed.
    EXPECT_EQ(s.methods[i].depthError.max, m["depthError"]["max"].get<double>());
    EXPECT_EQ(s.methods[i].worstDepth.size(), m["worstDepth"].size());
  }
  int placed = 0;
  for (const auto& [name, count] : s.placements) placed += count;
  EXPECT_EQ(placed, s.pairCount);
}

TEST(SatCheckSection, SummaryMarkdownEndsWithTheSectionOnlyWhenGiven) {
  const SatCheckSummary s = Fixture();
  const ResultsFile file;
  EXPECT_EQ(SummaryMarkdown(file).find("SAT validation"), std::string::npos);
  const std::string markdown = SummaryMarkdown(file, {.satCheck = &s});
  const std::size_t section = markdown.find("\n## SAT validation\n");
  ASSERT_NE(section, std::string::npos);
  EXPECT_EQ(markdown.substr(section + 1), SatCheckMarkdown(s));
}

TEST(SatCheckSection, MarkdownHasAgreementErrorsAndWorstCasesOfEveryMethod) {
  const SatCheckSummary s = Fixture();
  const std::string markdown = SatCheckMarkdown(s);
  for (const SatMethod& m : s.methods) {
    // One row in the verdict table, one in the distribution table, plus
    // one per listed worst case.
    std::size_t listed = std::min<std::size_t>(m.disagreements.size(), 5) +
                         std::min<std::size_t>(m.worstDepth.size(), 3) +
                         std::min<std::size_t>(m.worstNormal.size(), 3);
    EXPECT_EQ(Occurrences(markdown, "| " + m.name + " |"), 2 + listed) << m.name;
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.2f%%", 100.0 * m.agree / s.pairCount);
    EXPECT_NE(markdown.find("| " + m.name + " | " + m.family + " | " + rate + " |"), std::string::npos)
        << m.name;
  }
  const SatMethod& talus = s.methods.front();
  ASSERT_FALSE(talus.worstDepth.empty());
  EXPECT_NE(markdown.find("`" + talus.worstDepth.front().configuration + "`"), std::string::npos);
}

TEST(SatCheckSection, HtmlHasTheTablesThreePlotsAndTheirData) {
  const SatCheckSummary s = Fixture();
  const ResultsFile file;
  EXPECT_EQ(ReportHtml(file, "").find("sat-check"), std::string::npos);
  const std::string html = ReportHtml(file, "", "", {.satCheck = &s});
  EXPECT_EQ(Occurrences(html, "<h2 id=\"sat-validation\">SAT validation</h2>"), 1u);
  EXPECT_NE(html.find("id=\"sat-check-plots\""), std::string::npos);
  EXPECT_NE(html.find("type: 'logarithmic'"), std::string::npos);
  const std::string open = "<script type=\"application/json\" id=\"sat-check-data\">";
  const std::size_t begin = html.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = html.find("</script>", begin);
  const nlohmann::json data =
      nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
  ASSERT_EQ(data["methods"].size(), s.methods.size());
  for (std::size_t i = 0; i < s.methods.size(); ++i) {
    EXPECT_EQ(data["methods"][i]["name"], s.methods[i].name);
    if (s.methods[i].timeNs.count > 0) {
      EXPECT_EQ(data["methods"][i]["timeNs"]["p50"], s.methods[i].timeNs.p50);
    }
  }
  // Three charts: depth error and normal angle percentiles, time vs error.
  EXPECT_EQ(Occurrences(html.substr(end), "percentileChart('"), 2u);
  EXPECT_NE(html.find("median time per query against median"), std::string::npos);
}

TEST(SatCheckSection, WriteReportPutsTheSectionInBothFiles) {
  const SatCheckSummary s = Fixture();
  const std::filesystem::path folder =
      std::filesystem::path(::testing::TempDir()) / "talus_sat_check_section_report";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  { std::ofstream(folder / "chart.js") << "/* chart */"; }
  ASSERT_TRUE(WriteReport(ResultsFile{}, folder, folder / "chart.js", {}, {.satCheck = &s}));
  const auto slurp = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  };
  EXPECT_NE(slurp(folder / "summary.md").find("## SAT validation"), std::string::npos);
  EXPECT_NE(slurp(folder / "report.html").find("id=\"sat-check-data\""), std::string::npos);
  std::filesystem::remove_all(folder);
}

// Each edit breaks the fixture in one place; the message names the source
// and the JSON path.
TEST(SatCheckSection, MalformedFilesAreRefusedNamingThePlace) {
  struct Case {
    const char* what;
    void (*edit)(nlohmann::json&);
    const char* message;
  };
  const Case cases[] = {
      {"no methods", [](nlohmann::json& j) { j.erase("methods"); }, "$.methods: missing"},
      {"empty methods", [](nlohmann::json& j) { j["methods"] = nlohmann::json::array(); },
       "$.methods: expected at least one method"},
      {"methods not an array", [](nlohmann::json& j) { j["methods"] = 3; }, "$.methods: expected an array"},
      {"percentile a string", [](nlohmann::json& j) { j["methods"][1]["depthError"]["p50"] = "small"; },
       "$.methods[1].depthError.p50: expected a finite number >= 0"},
      {"negative count", [](nlohmann::json& j) { j["methods"][0]["verdict"]["agree"] = -1; },
       "$.methods[0].verdict.agree: expected an integer >= 0"},
      {"more verdicts than pairs", [](nlohmann::json& j) { j["methods"][0]["verdict"]["agree"] = 100000; },
       "$.methods[0].verdict: expected agree + disagree + oracleFailures <= pairCount"},
      {"empty name", [](nlohmann::json& j) { j["methods"][2]["name"] = ""; },
       "$.methods[2].name: expected a non-empty string"},
      {"case without pair", [](nlohmann::json& j) { j["methods"][0]["worstDepth"][0].erase("pair"); },
       "$.methods[0].worstDepth[0].pair: missing"},
      {"no truth", [](nlohmann::json& j) { j.erase("truth"); }, "$.truth: missing"},
      {"settings not an object", [](nlohmann::json& j) { j["settings"] = nlohmann::json::array(); },
       "$.settings: expected an object"},
  };
  for (const Case& c : cases) {
    nlohmann::json json = FixtureJson();
    c.edit(json);
    const auto read = ParseSatCheckJson(json.dump(), "bad.json");
    ASSERT_FALSE(read) << c.what;
    EXPECT_EQ(read.GetError().message, std::string("bad.json: ") + c.message) << c.what;
  }
  const auto notJson = ParseSatCheckJson("{\"methods\": [", "cut.json");
  ASSERT_FALSE(notJson);
  EXPECT_EQ(notJson.GetError().message, "cut.json: not valid JSON");
  const auto missing = ReadSatCheckFile("/nonexistent/sat_check.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.GetError().message.find("/nonexistent/sat_check.json: cannot read"), std::string::npos);
}

}  // namespace sat_check_section_test
}  // namespace talus::harness
