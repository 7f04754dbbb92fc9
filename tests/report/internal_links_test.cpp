// Every internal link of a report with every section (runs with FAILs, a
// sweep, the stress envelope, the large scenes, the SAT check) lands on a
// heading that exists, in both files: report.html's href="#x" on an element
// with id="x" (ids unique over the page), summary.md's ](#x) on a heading
// whose anchor, by GitHub's rule written out here, is x. The sweep, stress
// and large-scene headings have anchors too, and the scorecard links to the
// sweep and large-scene sections it summarises.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/synthetic_results.h"
#include "talus/harness/report/report.h"
#include "talus/harness/report/sat_check_results.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/scenes/bench_run.h"
#include "talus/harness/stress/stress.h"

namespace talus::harness {
namespace internal_links_test {

// One run with one truth "a" of the given error.
RunResult Run(const std::string& runId, const std::string& backend, double error) {
  return testing_support::SyntheticRun(runId, backend, {testing_support::SyntheticTruth("a", error)}, 1e-5);
}

// Runs whose ids collide as anchors ("box[v0=1.5]", "box[v0=15]"), one named
// like a later section's heading ("goals"), and FAILs in several of them.
ResultsFile Results() {
  ResultsFile file;
  file.backends = {"talus", "ode-step", "ode-step-tuned"};
  for (const char* id : {"box[v0=1.5]", "box[v0=15]", "goals", "criteria"}) {
    file.results.push_back(Run(id, "talus", 0.0));
    file.results.push_back(Run(id, "ode-step", 0.5));
    file.results.push_back(Run(id, "ode-step-tuned", id[0] == 'g' ? 0.5 : 0.0));
  }
  return file;
}

ResultsFile Sweep() {
  ResultsFile sweep;
  sweep.backends = {"talus", "bullet"};
  sweep.results = {Run("g1[h=0.01]", "talus", 0.001), Run("g1[h=0.01]", "bullet", 0.005)};
  for (RunResult& r : sweep.results) r.sweepValues = {{"h", "0.01"}};
  return sweep;
}

std::vector<StressEntry> Stress() {
  StressEntry column{.axis = "column", .backend = "talus", .envelope = {}};
  column.envelope.lastPass = 24;
  column.envelope.firstFail = 25;
  column.envelope.probes = {{.value = 24, .pass = true, .measure = 0.001, .detail = ""},
                            {.value = 25, .pass = false, .measure = 0.31, .detail = "top box moved"}};
  return {column};
}

std::vector<BenchReport> Scenes() {
  std::vector<BenchReport> scenes;
  for (const char* engine : {"talus", "bullet-f32"}) {
    BenchReport r;
    r.engine = engine;
    r.scene = "pyramid";
    r.parameter = 15;
    r.bodies = 1240;
    r.steps = 600;
    r.totalMs = 1200.0;
    r.msMean = 2.0;
    r.msMax = 2.0;
    r.drift = 0.01;
    scenes.push_back(r);
  }
  // talus again on two threads, both with stage times: the thread-scaling
  // and where-the-time-goes headings, and the link to the first.
  scenes[0].stages = {{"FindContacts", 0.5, 0.5}, {"SolveVelocities", 1.0, 1.0}};
  BenchReport twoThreads = scenes[0];
  twoThreads.threads = 2;
  twoThreads.totalMs = 900.0;
  twoThreads.msMean = 1.5;
  twoThreads.msMax = 1.5;
  scenes.push_back(twoThreads);
  return scenes;
}

// The value of every `attribute="..."` on the page whose value starts with
// `start` (e.g. href="#...").
std::vector<std::string> Attributes(const std::string& html, const std::string& attribute,
                                    const std::string& start = "") {
  std::vector<std::string> values;
  const std::string open = attribute + "=\"" + start;
  for (std::size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
    const std::size_t begin = at + attribute.size() + 2;
    values.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  return values;
}

// GitHub's heading anchor: lower case; letters, digits, '-' and '_' kept,
// spaces become '-', everything else dropped; the n-th repeat gets "-n".
std::set<std::string> MarkdownAnchors(const std::string& markdown) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  std::istringstream in(markdown);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hashes = line.find_first_not_of('#');
    if (hashes == 0 || hashes == std::string::npos || line[hashes] != ' ') continue;
    std::string base;
    for (const char c : line.substr(hashes + 1)) {
      const auto u = static_cast<unsigned char>(c);
      if (std::isalnum(u) || c == '-' || c == '_') base += static_cast<char>(std::tolower(u));
      if (c == ' ') base += '-';
    }
    const int repeat = seen[base]++;
    anchors.insert(repeat == 0 ? base : base + "-" + std::to_string(repeat));
  }
  return anchors;
}

// Every "](#x)" of the markdown.
std::vector<std::string> MarkdownLinks(const std::string& markdown) {
  std::vector<std::string> links;
  for (std::size_t at = markdown.find("](#"); at != std::string::npos; at = markdown.find("](#", at + 1)) {
    const std::size_t begin = at + 3;
    links.push_back(markdown.substr(begin, markdown.find(')', begin) - begin));
  }
  return links;
}

class InternalLinks : public ::testing::Test {
 protected:
  void SetUp() override {
    auto sat = ReadSatCheckFile(std::filesystem::path(TALUS_TEST_DATA_DIR) / "sat_check" / "small.json");
    ASSERT_TRUE(sat) << sat.GetError().message;
    m_sat = sat.Value();
    m_extras = {.satCheck = &m_sat, .sweep = &m_sweep, .stress = &m_stress, .scenes = &m_scenes};
  }
  ResultsFile m_results = Results();
  ResultsFile m_sweep = Sweep();
  std::vector<StressEntry> m_stress = Stress();
  std::vector<BenchReport> m_scenes = Scenes();
  SatCheckSummary m_sat;
  ReportExtras m_extras;
};

TEST_F(InternalLinks, EveryHtmlLinkLandsOnOneElement) {
  const std::string html = ReportHtml(m_results, "/* chart */", "", m_extras);
  std::map<std::string, int> ids;
  for (const std::string& id : Attributes(html, "id")) ++ids[id];
  for (const auto& [id, count] : ids)
    EXPECT_EQ(count, 1) << "id \"" << id << "\" appears " << count << " times";
  const std::vector<std::string> links = Attributes(html, "href", "#");
  EXPECT_GE(links.size(), 10u);
  for (const std::string& link : links) EXPECT_EQ(ids.count(link.substr(1)), 1u) << "dangling link " << link;
  // Every section heading is a link target, the extras' ones included.
  for (const char* tag : {"<h2", "<h3"}) {
    for (std::size_t at = html.find(tag); at != std::string::npos; at = html.find(tag, at + 1)) {
      EXPECT_EQ(html.compare(at + 3, 5, " id=\""), 0) << html.substr(at, 80);
    }
  }
  for (const char* section : {"run-time-against-error", "stability-envelope", "large-scenes",
                              "thread-scaling", "where-the-time-goes", "pyramid-h--15-where-the-time-goes"})
    EXPECT_EQ(ids.count(section), 1u) << section;
  EXPECT_NE(html.find("<a href=\"#thread-scaling\">"), std::string::npos);
  // The scorecard points at the sections its sweep and scenes columns summarise.
  EXPECT_NE(html.find("<a href=\"#run-time-against-error\">"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#large-scenes\">"), std::string::npos);
}

TEST_F(InternalLinks, EveryMarkdownLinkLandsOnAHeading) {
  const std::string md = SummaryMarkdown(m_results, m_extras);
  const std::set<std::string> anchors = MarkdownAnchors(md);
  const std::vector<std::string> links = MarkdownLinks(md);
  EXPECT_GE(links.size(), 10u);
  for (const std::string& link : links) EXPECT_EQ(anchors.count(link), 1u) << "dangling link #" << link;
  for (const char* section : {"run-time-against-error", "stability-envelope", "large-scenes",
                              "thread-scaling", "where-the-time-goes", "pyramid-h--15-where-the-time-goes"})
    EXPECT_EQ(anchors.count(section), 1u) << section;
  EXPECT_NE(md.find("](#thread-scaling)"), std::string::npos);
  EXPECT_NE(md.find("](#where-the-time-goes)"), std::string::npos);
  EXPECT_NE(md.find("](#run-time-against-error)"), std::string::npos);
  EXPECT_NE(md.find("](#large-scenes)"), std::string::npos);
}

}  // namespace internal_links_test
}  // namespace talus::harness
