// The report's opening scorecard (report_scorecard.h).
#include "report/report_scorecard.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report/report_peers.h"
#include "support/text_util.h"
#include "talus/harness/report/bench_summary.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {
namespace {

// A truth the report judges: it has a tolerance, gated by the CI check or
// shown as ungated.
bool Judged(const MetricResult& m) { return m.checked || !m.ungated.empty(); }

// The cause of one FAIL of `backend`; `setting` says whether its tuned
// counterpart removes it.
std::string Cause(const std::string& backend, const MetricResult& failed,
                  const std::map<std::string, const RunResult*>& byBackend, bool& setting) {
  setting = false;
  const std::string tunedName = TunedName(backend);
  const auto tuned = byBackend.find(tunedName);
  if (tunedName.empty()) {
    // A tuned configuration's FAIL: the defaults' verdict on the same truth
    // says whether the tuned settings added it.
    const std::string defaultsName = backend.substr(0, backend.size() - std::string_view("-tuned").size());
    const auto defaults = byBackend.find(defaultsName);
    const RunResult* run = defaults == byBackend.end() ? nullptr : defaults->second;
    const MetricResult* own = run != nullptr && run->error.empty() ? FindMetric(*run, failed.name) : nullptr;
    if (own == nullptr || !Judged(*own) || !own->pass)
      return "the engine's own behaviour, in its tuned configuration";
    int otherFails = 0;
    for (const MetricResult& m : run->metrics) otherFails += Judged(m) && !m.pass ? 1 : 0;
    if (otherFails > 0) {
      return Concat({"the engine's own behaviour: `", defaultsName, "` passes this truth (",
                     FormatNumber(own->error, 3), ") but FAILs ", std::to_string(otherFails),
                     " other truths of this run, which goes wrong in both configurations"});
    }
    setting = true;
    return Concat({"the tuned settings add it: `", defaultsName, "` passes (", FormatNumber(own->error, 3),
                   "); the engine's settings section gives each tuned setting's measured trade"});
  }
  if (tuned == byBackend.end()) {
    return "the engine's own behaviour in this configuration (no `-tuned` counterpart ran)";
  }
  const MetricResult* other =
      tuned->second->error.empty() ? FindMetric(*tuned->second, failed.name) : nullptr;
  if (other == nullptr || !Judged(*other)) {
    return Concat({"not separated: `", tunedName, "` did not measure it"});
  }
  if (other->pass) {
    setting = true;
    return Concat({"a setting: removed by `", tunedName, "` (", FormatNumber(other->error, 3), ")"});
  }
  return Concat(
      {"the engine's own behaviour: not removed by `", tunedName, "` (", FormatNumber(other->error, 3), ")"});
}

// The main results grouped by run id, in first-appearance order.
std::vector<std::pair<std::string, std::map<std::string, const RunResult*>>> ByRun(const ResultsFile& file) {
  std::vector<std::pair<std::string, std::map<std::string, const RunResult*>>> runs;
  for (const RunResult& r : file.results) {
    if (runs.empty() || runs.back().first != r.runId) runs.push_back({r.runId, {}});
    runs.back().second[r.backend] = &r;
  }
  return runs;
}

ScorecardRow& RowOf(Scorecard& card, const std::string& backend) {
  for (ScorecardRow& row : card.rows) {
    if (row.backend == backend) return row;
  }
  card.rows.push_back({});
  card.rows.back().backend = backend;
  return card.rows.back();
}

std::string Fraction(int part, int whole) {
  if (whole == 0) return "-";
  return Concat({std::to_string(part), " of ", std::to_string(whole), " (",
                 FormatNumber(100.0 * part / whole, 3), "%)"});
}

constexpr const char* kChartScript = R"(
document.addEventListener('DOMContentLoaded', () => {
  const card = JSON.parse(document.getElementById('scorecard-data').textContent);
  new Chart(document.getElementById('scorecard-chart'), {type: 'bar',
    data: {labels: card.backends, datasets: [{label: 'truths passed / judged', data: card.fractions,
      backgroundColor: card.fractions.map(f => f === 1 ? '#2ca02c' : '#d62728')}]},
    options: {indexAxis: 'y', animation: false, maintainAspectRatio: false,
      scales: {x: {min: 0, max: 1, title: {display: true, text: 'fraction of judged truths passed'}}},
      plugins: {title: {display: true, text: 'Scorecard: truths passed per engine and configuration'},
                tooltip: {callbacks: {label: c => card.passed[c.dataIndex] + ' of ' + card.judged[c.dataIndex] +
                  ' truths passed'}}}}});
});
)";

}  // namespace

const MetricResult* FindMetric(const RunResult& r, const std::string& name) {
  for (const MetricResult& m : r.metrics) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string HeadingAnchor(std::string_view heading) {
  std::string anchor;
  for (char c : heading) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '-' || c == '_') {
      anchor += static_cast<char>(std::tolower(u));
    } else if (c == ' ') {
      anchor += '-';
    }
  }
  return anchor;
}

std::map<std::string, std::string> RunAnchors(const ResultsFile& file) {
  // The headings summary.md has before the run sections.
  std::map<std::string, int> seen = {{"talus-testbed-report", 1}, {"scorecard", 1}, {"overview", 1}};
  std::map<std::string, std::string> anchors;
  for (const auto& [runId, byBackend] : ByRun(file)) {
    if (anchors.count(runId)) continue;
    const std::string base = HeadingAnchor(runId);
    const int repeat = seen[base]++;
    anchors[runId] = repeat == 0 ? base : Concat({base, "-", std::to_string(repeat)});
  }
  return anchors;
}

Scorecard BuildScorecard(const ResultsFile& file, const ReportExtras& extras) {
  Scorecard card;
  const std::map<std::string, std::string> anchors = RunAnchors(file);
  for (const std::string& b : file.backends) RowOf(card, b);
  for (const auto& [runId, byBackend] : ByRun(file)) {
    for (const auto& [backend, result] : byBackend) {
      ScorecardRow& row = RowOf(card, backend);
      ++row.runs;
      if (!result->error.empty()) {
        ++row.runsStopped;
        row.failRuns.push_back({runId, anchors.at(runId), -1});
        continue;
      }
      int fails = 0;
      for (const MetricResult& m : result->metrics) {
        if (!Judged(m)) continue;
        ++row.judged;
        if (m.pass) {
          ++row.passed;
          continue;
        }
        ++fails;
        bool setting = false;
        Cause(backend, m, byBackend, setting);
        if (setting) ++row.settingFails;
      }
      if (fails == 0) {
        ++row.runsPassing;
      } else {
        row.failRuns.push_back({runId, anchors.at(runId), fails});
      }
    }
  }
  if (extras.sweep != nullptr) {
    card.hasSweep = true;
    // The sweep section's own comparison (CompareFronts), counted per backend.
    for (const SweepGroup& group : AnalyseSweep(*extras.sweep, kSweepSingleSetting)) {
      for (std::size_t b = 0; b < group.backends.size(); ++b) {
        ScorecardRow& row = RowOf(card, group.backends[b]);
        ++row.sweepGroups;
        if (group.comparison.winner == static_cast<int>(b)) ++row.sweepWins;
      }
    }
  }
  if (extras.scenes != nullptr) {
    for (const BenchReport& r : *extras.scenes) RowOf(card, r.engine);
    for (const BenchHeadline& headline : BenchHeadlines(*extras.scenes)) {
      card.scenes.push_back(headline.title);
      for (ScorecardRow& row : card.rows) {
        const auto cell = headline.cellByEngine.find(row.backend);
        row.sceneCells.push_back(cell == headline.cellByEngine.end() ? "-" : cell->second);
      }
    }
  }
  return card;
}

std::string ScorecardMarkdown(const Scorecard& card) {
  std::ostringstream out;
  out << "## Scorecard\n\n| engine / configuration | truths passed | runs fully passing | runs stopped | "
         "FAILs a setting causes |";
  if (card.hasSweep) out << " most accurate at equal cost |";
  for (const std::string& scene : card.scenes) out << " " << scene << " |";
  out << " runs with a FAIL |\n|---|---|---|---|---|";
  if (card.hasSweep) out << "---|";
  for (std::size_t i = 0; i < card.scenes.size(); ++i) out << "---|";
  out << "---|\n";
  for (const ScorecardRow& row : card.rows) {
    out << "| " << row.backend << " | " << Fraction(row.passed, row.judged) << " | "
        << (row.runs == 0 ? std::string("-")
                          : Concat({std::to_string(row.runsPassing), " of ", std::to_string(row.runs)}))
        << " | " << (row.runs == 0 ? std::string("-") : std::to_string(row.runsStopped)) << " | "
        << (row.runs == 0 ? std::string("-") : std::to_string(row.settingFails)) << " |";
    if (card.hasSweep) {
      out << " "
          << (row.sweepGroups == 0
                  ? std::string("-")
                  : Concat({std::to_string(row.sweepWins), " of ", std::to_string(row.sweepGroups)}))
          << " |";
    }
    for (const std::string& cell : row.sceneCells) out << " " << cell << " |";
    std::string links;
    for (const FailedRun& run : row.failRuns) {
      links.append(links.empty() ? "" : ", ")
          .append(Concat({"[", run.runId, "](#", run.anchor, ") (",
                          run.fails < 0 ? std::string("stopped") : std::to_string(run.fails), ")"}));
    }
    out << " " << (links.empty() ? std::string("-") : links) << " |\n";
  }
  out << "\nTruths passed: metrics with a tolerance (gated by `talus-testbed check` or shown as ungated) "
         "within "
         "it, out of those judged in the runs that did not stop. A FAIL a setting causes is one of a "
         "`defaults` configuration that its `-tuned` configuration removes, or one of a `-tuned` "
         "configuration in a run its `defaults` pass entirely (the tuned settings add it); each run with a "
         "FAIL links to its section, which names every FAIL's cause.";
  if (card.hasSweep)
    out << " Most accurate at equal cost: the sweep groups the configuration wins out of those it is "
           "compared in ([Run time against error](#run-time-against-error)).";
  if (!card.scenes.empty())
    out << " Mean ms/step: the run's total wall time / steps on the large scenes at their reference size, "
           "or the largest run, each engine at its defaults on one thread ([Large scenes](#large-scenes)).";
  out << "\n\n";
  return out.str();
}

std::string ScorecardChartHtml(const Scorecard& card) {
  nlohmann::ordered_json data;
  data["backends"] = nlohmann::ordered_json::array();
  data["fractions"] = nlohmann::ordered_json::array();
  data["passed"] = nlohmann::ordered_json::array();
  data["judged"] = nlohmann::ordered_json::array();
  for (const ScorecardRow& row : card.rows) {
    if (row.judged == 0) continue;
    data["backends"].push_back(row.backend);
    data["fractions"].push_back(static_cast<double>(row.passed) / row.judged);
    data["passed"].push_back(row.passed);
    data["judged"].push_back(row.judged);
  }
  if (data["backends"].empty()) return "";
  std::ostringstream out;
  out << "<div class=\"plots\"><div class=\"plot\"><canvas id=\"scorecard-chart\"></canvas></div></div>\n"
      << "<script type=\"application/json\" id=\"scorecard-data\">" << ScriptSafe(data.dump())
      << "</script>\n"
      << "<script>" << kChartScript << "</script>\n";
  return out.str();
}

std::string FailCauseLines(const std::vector<std::string>& backends,
                           const std::map<std::string, const RunResult*>& byBackend) {
  std::ostringstream out;
  for (const std::string& backend : backends) {
    const auto own = byBackend.find(backend);
    if (own == byBackend.end() || !own->second->error.empty()) continue;
    for (const MetricResult& m : own->second->metrics) {
      if (!Judged(m) || m.pass) continue;
      bool setting = false;
      out << "- `" << backend << "` FAILs " << m.name << (m.ungated.empty() ? "" : " (ungated)") << " ("
          << FormatNumber(m.error, 3) << "): " << Cause(backend, m, byBackend, setting) << "\n";
    }
  }
  return out.str();
}

}  // namespace talus::harness
