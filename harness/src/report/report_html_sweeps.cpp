// The HTML of the sweep and stress analyses: the run-time-against-error
// section of report.html (SweepHtmlSection, called once where the page is
// assembled in report_html.cpp) and the stress envelope page
// (StressHtml). Tables come from the Markdown texts (sweep.h, stress.h),
// converted here with a small pipe-table converter, so the HTML and the
// Markdown never disagree; charts are drawn by the page's Chart.js.
#include <algorithm>
#include <sstream>

#include "support/text_util.h"
#include "talus/harness/stress/stress.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {
namespace {

// Headings, pipe tables and paragraphs; enough for the texts of sweep.h
// and stress.h.
std::string TablesToHtml(const std::string& markdown) {
  std::istringstream in(markdown);
  std::ostringstream out;
  std::string line;
  bool inTable = false;
  bool header = false;
  while (std::getline(in, line)) {
    const bool row = !line.empty() && line[0] == '|';
    if (inTable && !row) {
      out << "</table>\n";
      inTable = false;
    }
    if (row) {
      if (line.rfind("|---", 0) == 0) continue;
      if (!inTable) {
        out << "<table>\n";
        inTable = header = true;
      }
      out << "<tr>";
      std::string cell;
      for (std::size_t i = 1; i < line.size(); ++i) {
        if (line[i] != '|') {
          cell += line[i];
          continue;
        }
        const auto first = cell.find_first_not_of(' ');
        const std::string text =
            first == std::string::npos ? "" : cell.substr(first, cell.find_last_not_of(' ') - first + 1);
        const char* tag = header ? "th" : "td";
        out << "<" << tag
            << (text == "FAIL" ? " class=\"fail\""
                : text == "ok" ? " class=\"ok\""
                               : "")
            << ">" << EscapeHtml(text) << "</" << tag << ">";
        cell.clear();
      }
      out << "</tr>\n";
      header = false;
    } else if (line.rfind("### ", 0) == 0) {
      out << "<h3>" << EscapeHtml(line.substr(4)) << "</h3>\n";
    } else if (line.rfind("## ", 0) == 0) {
      out << "<h2>" << EscapeHtml(line.substr(3)) << "</h2>\n";
    } else if (!line.empty()) {
      out << "<p>" << EscapeHtml(line) << "</p>\n";
    }
  }
  if (inTable) out << "</table>\n";
  return out.str();
}

// One log-log chart per group: a line per curve (backend, iterations), its
// Pareto points drawn large; errors of 0 are drawn at 1e-12 and costs of 0
// (deterministic mode) at 1e-9 s, since a log axis cannot show 0;
// unmeasured (infinite) errors are left out.
constexpr const char* kSweepScript = R"(
(function() {
  const sweep = JSON.parse(document.getElementById('sweep-data').textContent);
  const section = document.getElementById('sweep-plots');
  const palette = ['#1f77b4','#d62728','#2ca02c','#ff7f0e','#9467bd','#8c564b','#e377c2','#7f7f7f'];
  const dashes = [[], [6, 3], [2, 2], [8, 2, 2, 2]];
  for (const group of sweep.groups) {
    const box = document.createElement('div'); box.className = 'plot';
    const canvas = document.createElement('canvas'); box.appendChild(canvas); section.appendChild(box);
    const iterationsSeen = {};
    const datasets = group.curves.map(curve => {
      const k = group.backends.indexOf(curve.backend);
      const seen = iterationsSeen[curve.backend] = (iterationsSeen[curve.backend] || 0) + 1;
      const points = curve.points.filter(p => p.error !== null);
      return {label: curve.backend + ' it=' + (curve.iterations || 'default'), showLine: true,
              borderColor: palette[k % palette.length], backgroundColor: palette[k % palette.length],
              borderDash: dashes[(seen - 1) % dashes.length], borderWidth: 1,
              pointRadius: points.map(p => p.front ? 5 : 2),
              pointStyle: points.map(p => p.front ? 'rectRot' : 'circle'),
              data: points.map(p => ({x: Math.max(p.cost, 1e-9), y: Math.max(p.error, 1e-12), h: p.timeStep}))};
    });
    const winner = group.winner === null ? 'no single winner' : 'most accurate at equal cost: ' + group.winner;
    new Chart(canvas, {type: 'scatter', data: {datasets: datasets}, options: {animation: false,
      maintainAspectRatio: false,
      plugins: {title: {display: true, text: group.id + ' (' + winner + '; large diamonds: Pareto front)'},
                tooltip: {callbacks: {label: c => c.dataset.label + ' h=' + c.raw.h.toPrecision(3) +
                  ' s: cost ' + c.raw.x.toPrecision(3) + ' s, error ' + c.raw.y.toPrecision(3)}}},
      scales: {x: {type: 'logarithmic', title: {display: true, text: 'run time (s)'}},
               y: {type: 'logarithmic', title: {display: true, text: 'error / tolerance'}}}}});
  }
})();
)";

}  // namespace

std::string SweepHtmlSection(const ResultsFile& file) {
  const bool swept = std::any_of(file.results.begin(), file.results.end(), [](const RunResult& r) {
    return std::any_of(r.sweepValues.begin(), r.sweepValues.end(),
                       [](const SweepValue& v) { return v.name == "h"; });
  });
  if (!swept) return "";
  const std::vector<SweepGroup> groups = AnalyseSweep(file, kSweepSingleSetting);
  std::ostringstream out;
  out << TablesToHtml(SweepMarkdown(groups));
  out << "<div class=\"plots\" id=\"sweep-plots\"></div>\n";
  out << "<script type=\"application/json\" id=\"sweep-data\">" << ScriptSafe(SweepToJson(groups))
      << "</script>\n";
  out << "<script>" << kSweepScript << "</script>\n";
  return out.str();
}

std::string StressHtml(const std::vector<StressEntry>& entries) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Talus stability "
         "envelope</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:90em}"
         "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.25em .6em;"
         "text-align:left}th{background:#eee}td.ok{background:#e6f4e6}td.fail{background:#f8d7d7}</style>\n"
         "</head>\n<body>\n"
      << TablesToHtml(StressMarkdown(entries)) << "</body>\n</html>\n";
  return out.str();
}

}  // namespace talus::harness
