// report.html and the writing of every report file (report.h).
//
// The page's tables are summary.md's, converted line by line (headings,
// pipe tables, paragraphs), so the two never disagree. The plots are drawn
// in the browser by the inlined charting library from the results' plot
// series, embedded as JSON in a <script type="application/json"> element:
// per run, the height of every body that moves and the total energy over
// time, one line per backend and body; and the total wall time of every
// backend's run, as bars.
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "report/markdown_html.h"
#include "report/report_html_replay.h"
#include "report/report_scorecard.h"
#include "support/text_util.h"
#include "talus/harness/report/bench_summary.h"
#include "talus/harness/report/report.h"
#include "talus/harness/report/sat_check_results.h"
#include "talus/harness/run/display_trajectory.h"
#include "talus/harness/support/atomic_file.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {
namespace {

// What the page's script plots, as JSON, in the display form (the page
// draws the same lines from it; display_trajectory.h).
nlohmann::ordered_json PlotData(const ResultsFile& file) {
  nlohmann::ordered_json data;
  data["backends"] = file.backends;
  data["runs"] = nlohmann::ordered_json::array();
  for (const RunResult& r : file.results) {
    if (data["runs"].empty() || data["runs"].back()["id"] != r.runId) {
      data["runs"].push_back(
          {{"id", r.runId}, {"bodies", r.bodyNames}, {"results", nlohmann::ordered_json::array()}});
    }
    const PlotSeries shown = file.trajectoriesInDisplayForm ? r.series : DisplaySeries(r.series);
    nlohmann::ordered_json entry;
    entry["backend"] = r.backend;
    entry["wallSeconds"] = r.wallSeconds;
    entry["time"] = shown.time;
    entry["heights"] = shown.heights;
    entry["energy"] = shown.energy;
    data["runs"].back()["results"].push_back(entry);
  }
  return data;
}

constexpr const char* kStyle = R"(body{font-family:sans-serif;margin:2em;max-width:90em}
table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.25em .6em;text-align:left}
th{background:#eee}td.ok{background:#e6f4e6}td.fail{background:#f8d7d7;font-weight:bold}
.plots{display:flex;flex-wrap:wrap;gap:1em}.plot{width:44em;height:22em}code{background:#f4f4f4})";

// The plots; their series come from report-data.js (kReportDataFile),
// loaded before this script, and a missing file is said in their place.
constexpr const char* kScript = R"(
(function () {
const section = document.getElementById('plots');
if (!window.talusReportData) {
  section.textContent = 'The plot data (report-data.js, written beside report.html) was not found: ' +
    'keep the two files together.';
  window.talusReport.errors.push('report-data.js was not found beside the page');
  return;
}
const data = window.talusReportData.plots;
const palette = ['#1f77b4','#d62728','#2ca02c','#ff7f0e','#9467bd','#8c564b','#e377c2','#7f7f7f'];
function addChart(title, config) {
  const box = document.createElement('div'); box.className = 'plot';
  const canvas = document.createElement('canvas'); box.appendChild(canvas); section.appendChild(box);
  config.options = Object.assign({animation:false, maintainAspectRatio:false,
    plugins:{title:{display:true,text:title}}}, config.options || {});
  new Chart(canvas, config);
}
function color(i) { return palette[i % palette.length]; }
const timeBars = {labels: [], datasets: data.backends.map((b, i) => ({label: b, data: [], backgroundColor: color(i)}))};
for (const run of data.runs) {
  const heights = [], energies = [];
  run.results.forEach(result => {
    const k = data.backends.indexOf(result.backend);
    result.heights.forEach((series, b) => {
      if (series.length < 2 || Math.max(...series) - Math.min(...series) < 1e-12) return;
      heights.push({label: result.backend + ' ' + run.bodies[b], borderColor: color(k), pointRadius: 0,
                    borderWidth: 1, data: series.map((y, j) => ({x: result.time[j], y: y}))});
    });
    if (result.energy.length > 1)
      energies.push({label: result.backend, borderColor: color(k), pointRadius: 0, borderWidth: 1,
                     data: result.energy.map((e, j) => ({x: result.time[j], y: e}))});
  });
  const axes = (y) => ({x:{type:'linear',title:{display:true,text:'time (s)'}},y:{title:{display:true,text:y}}});
  if (heights.length) addChart(run.id + ': height of the centre of mass',
                               {type:'line', data:{datasets:heights}, options:{scales:axes('m')}});
  if (energies.length) addChart(run.id + ': total energy',
                                {type:'line', data:{datasets:energies}, options:{scales:axes('J')}});
  timeBars.labels.push(run.id);
  timeBars.datasets.forEach(d => {
    const r = run.results.find(x => x.backend === d.label);
    d.data.push(r ? r.wallSeconds * 1e3 : null);
  });
}
addChart('wall time of the run (ms)', {type:'bar', data:timeBars,
  options:{scales:{y:{type:'logarithmic',title:{display:true,text:'ms'}}}}});
})();
)";

// The end of the <script> element starting at `at`, past its closing tag.
std::size_t ScriptEnd(const std::string& html, std::size_t at) {
  const std::size_t close = html.find("</script>", at);
  return close == std::string::npos ? html.size() : close + 9;
}

// Whether a heading tag <h2>, <h3> or <h4> (with or without attributes)
// opens at `at`.
bool HeadingAt(const std::string& html, std::size_t at) {
  return at + 3 < html.size() && html.compare(at, 2, "<h") == 0 && html[at + 2] >= '2' &&
         html[at + 2] <= '4' && (html[at + 3] == '>' || html[at + 3] == ' ');
}

// The page with an id on every <h2> to <h4> outside scripts, each unique
// over the page. The page is put together from several conversions (the
// runs, the SAT, sweep, stress and large-scene sections), each numbering
// only its own repeats, and some sections write headings without ids. In
// page order: a heading keeps its id (or gets its text's anchor) unless an
// earlier heading or any other element (the scripts' containers) holds it,
// and then gets "-1", "-2"... as GitHub numbers repeats; summary.md's
// headings come in the same order, so the links of both files agree.
std::string WithUniqueHeadingIds(const std::string& html) {
  std::set<std::string> used;
  for (std::size_t at = html.find(" id=\""); at != std::string::npos; at = html.find(" id=\"", at + 1)) {
    const std::size_t open = html.rfind('<', at);
    if (open != std::string::npos && HeadingAt(html, open)) continue;
    const std::size_t begin = at + 5;
    used.insert(html.substr(begin, html.find('"', begin) - begin));
  }
  std::string out;
  out.reserve(html.size() + 1024);
  std::size_t at = 0;
  while (at < html.size()) {
    if (html.compare(at, 7, "<script") == 0) {
      const std::size_t end = ScriptEnd(html, at);
      out.append(html, at, end - at);
      at = end;
      continue;
    }
    if (!HeadingAt(html, at)) {
      out += html[at++];
      continue;
    }
    const std::size_t tagEnd = html.find('>', at);
    const std::size_t close = html.find("</h", tagEnd);
    if (tagEnd == std::string::npos || close == std::string::npos) {
      out.append(html, at, std::string::npos);
      break;
    }
    std::string base;
    if (html.compare(at + 3, 5, " id=\"") == 0) {
      base = html.substr(at + 8, html.find('"', at + 8) - (at + 8));
    } else {
      std::string text;  // the heading's text without tags
      bool inTag = false;
      for (std::size_t i = tagEnd + 1; i < close; ++i) {
        if (html[i] == '<' || html[i] == '>') {
          inTag = html[i] == '<';
        } else if (!inTag) {
          text += html[i];
        }
      }
      base = HeadingAnchor(text);
    }
    std::string id = base;
    for (int repeat = 1; used.count(id) != 0; ++repeat) id = Concat({base, "-", std::to_string(repeat)});
    used.insert(id);
    out.append(html, at, 3).append(Concat({" id=\"", id, "\""}));
    out.append(html, tagEnd, close - tagEnd);
    at = close;
  }
  return out;
}

}  // namespace

std::string ReportHtml(const ResultsFile& file, std::string_view chartLibrary, std::string_view threeLibrary,
                       const ReportExtras& extras) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<title>Talus testbed report</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
  // The scorecard opens the page, its chart beside its table (drawn once the
  // charting library below is loaded).
  const Scorecard card = BuildScorecard(file, extras);
  // One conversion, so repeated heading anchors are numbered over the whole
  // page as RunAnchors numbers them; the chart goes in before the overview.
  std::string tables = MarkdownToHtml(SummaryTitle(file) + ScorecardMarkdown(card) + SummaryRuns(file));
  tables.insert(tables.find("<h2 id=\"overview\">"), ScorecardChartHtml(card));
  out << tables;
  out << "<h2>Plots</h2>\n<div class=\"plots\" id=\"plots\"></div>\n";
  // The series and replays: most of a report's bytes, in their own files.
  out << "<script src=\"" << kReportDataFile << "\"></script>\n";
  out << "<script src=\"" << kReportReplayFile << "\"></script>\n";
  out << "<script>\n" << ScriptSafe(std::string(chartLibrary)) << "\n</script>\n";
  out << ReplaySections(file, threeLibrary);
  out << "<script>" << kScript << "</script>\n";
  out << SweepHtmlSection(file);
  if (extras.satCheck != nullptr) out << SatCheckHtmlSection(*extras.satCheck);
  if (extras.sweep != nullptr) out << SweepHtmlSection(*extras.sweep);
  if (extras.stress != nullptr) out << MarkdownToHtml(StressMarkdown(*extras.stress));
  if (extras.scenes != nullptr) out << BenchHtmlSection(*extras.scenes);
  out << "</body>\n</html>\n";
  return WithUniqueHeadingIds(out.str());
}

std::string ReportDataScript(const ResultsFile& file) {
  nlohmann::ordered_json data;
  data["plots"] = PlotData(file);
  return Concat(
      {"// The plot series of report.html (talus-testbed report), loaded by the page.\n"
       "window.talusReportData = ",
       data.dump(), ";\n"});
}

std::string ReportReplayScript(const ResultsFile& file) {
  return Concat(
      {"// The replays of report.html (talus-testbed report), loaded by the page.\n"
       "window.talusReportReplays = ",
       ReplayRunsForPage(file).dump(), ";\n"});
}

Result<std::monostate> WriteReport(const ResultsFile& file, const std::filesystem::path& folder,
                                   const std::filesystem::path& chartLibraryPath,
                                   const std::filesystem::path& threeLibraryPath,
                                   const ReportExtras& extras) {
  std::ifstream library(chartLibraryPath, std::ios::binary);
  if (!library) {
    return Error{Concat({chartLibraryPath.string(),
                         ": charting library not found (run scripts/install-deps.sh, which runs npm ci in "
                         "harness/report)"})};
  }
  std::ostringstream js;
  js << library.rdbuf();
  std::ostringstream three;
  if (!threeLibraryPath.empty()) {
    std::ifstream threeFile(threeLibraryPath, std::ios::binary);
    if (!threeFile) {
      return Error{Concat({threeLibraryPath.string(),
                           ": three.js not found (run scripts/install-deps.sh, which runs npm ci in "
                           "harness/report)"})};
    }
    three << threeFile.rdbuf();
  }
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error)
    return Error{Concat({folder.string(), ": cannot make the report folder (", error.message(), ")"})};
  // One set: a full disk or a failed rename leaves the folder as it was,
  // never a new summary beside an old page.
  std::vector<FileText> files = {
      {folder / "summary.md", SummaryMarkdown(file, extras)},
      {folder / "results.csv", ResultsCsv(file)},
  };
  for (FileText& text : ResultsFileTexts(folder / "results.json", file)) files.push_back(std::move(text));
  files.push_back({folder / "report.html", ReportHtml(file, js.str(), three.str(), extras)});
  files.push_back({folder / kReportDataFile, ReportDataScript(file)});
  files.push_back({folder / kReportReplayFile, ReportReplayScript(file)});
  return WriteFilesAtomically(files);
}

}  // namespace talus::harness
