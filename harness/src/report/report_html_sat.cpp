// The SAT validation section of report.html (SatCheckHtmlSection, called
// once where the page is assembled in report_html.cpp): the tables of
// SatCheckMarkdown converted to HTML, so the page and summary.md never
// disagree, then three Chart.js plots drawn from the summary embedded as
// JSON:
//   - depth error percentiles (p50, p90, p99, max) per method, log scale;
//   - normal angle percentiles per method, log scale;
//   - median time per query against median depth error, one point per
//     method that reports a depth, log-log (the issue's "time per query
//     against accuracy").
// A log axis cannot show 0, and Talus's depth errors are often exactly 0,
// so values are drawn at a floor of 1e-18 (m or rad, far below double
// rounding of metre-sized shapes, ~1e-16) and the axis says so.
#include <nlohmann/json.hpp>
#include <sstream>

#include "report/markdown_html.h"
#include "support/text_util.h"
#include "talus/harness/report/sat_check_results.h"

namespace talus::harness {
namespace {

using Json = nlohmann::ordered_json;

Json DistributionJson(const SatDistribution& d) {
  if (d.count == 0) return nullptr;
  return {{"count", d.count}, {"p50", d.p50}, {"p90", d.p90}, {"p99", d.p99}, {"max", d.max}};
}

// What the section's script plots.
Json PlotJson(const SatCheckSummary& s) {
  Json methods = Json::array();
  for (const SatMethod& m : s.methods) {
    methods.push_back({{"name", m.name},
                       {"family", m.family},
                       {"givesDepth", m.givesDepth},
                       {"depthError", DistributionJson(m.depthError)},
                       {"normalAngle", DistributionJson(m.normalAngle)},
                       {"timeNs", DistributionJson(m.timeNs)}});
  }
  return {{"pairCount", s.pairCount}, {"seed", s.seed}, {"methods", methods}};
}

// Colours by family (Talus blues, libccd reds, Bullet greens), shade by
// position within the family, so a method keeps its colour in every plot.
constexpr const char* kSatScript = R"(
(function() {
  const sat = JSON.parse(document.getElementById('sat-check-data').textContent);
  const section = document.getElementById('sat-check-plots');
  const floor = 1e-18;
  const shades = {talus: ['#08306b','#08519c','#2171b5','#4292c6','#6baed6','#9ecae1','#3182bd','#c6dbef'],
                  libccd: ['#a50f15','#de2d26','#fb6a4a','#fc9272'], bullet: ['#006d2c','#31a354','#74c476']};
  const used = {};
  const colours = sat.methods.map(m => {
    const list = shades[m.family] || ['#7f7f7f'];
    used[m.family] = (used[m.family] || 0) + 1;
    return list[(used[m.family] - 1) % list.length];
  });
  function addChart(config) {
    const box = document.createElement('div'); box.className = 'plot';
    const canvas = document.createElement('canvas'); box.appendChild(canvas); section.appendChild(box);
    config.options = Object.assign({animation: false, maintainAspectRatio: false}, config.options);
    new Chart(canvas, config);
  }
  function percentileChart(key, title, unit) {
    const shown = sat.methods.filter(m => m[key] !== null);
    const levels = [['p50', '#9ecae1'], ['p90', '#4292c6'], ['p99', '#08519c'], ['max', '#d62728']];
    addChart({type: 'bar', data: {labels: shown.map(m => m.name), datasets: levels.map(([p, c]) => ({
        label: p, backgroundColor: c, data: shown.map(m => Math.max(m[key][p], floor))}))},
      options: {plugins: {title: {display: true, text: title + ' per method (' + sat.pairCount + ' pairs)'}},
                scales: {y: {type: 'logarithmic', min: floor,
                             title: {display: true, text: unit + ' (0 drawn at 1e-18)'}}}}});
  }
  percentileChart('depthError', 'SAT validation: depth error |d - d*|', 'm');
  percentileChart('normalAngle', 'SAT validation: normal angle to the truth', 'rad');
  const points = sat.methods.map((m, i) => ({m: m, c: colours[i]}))
      .filter(e => e.m.givesDepth && e.m.depthError !== null && e.m.timeNs !== null && e.m.timeNs.p50 > 0);
  addChart({type: 'scatter', data: {datasets: points.map(e => ({label: e.m.name, backgroundColor: e.c,
      borderColor: e.c, pointRadius: 6, pointStyle: e.m.family === 'talus' ? 'rectRot' : 'circle',
      data: [{x: e.m.timeNs.p50, y: Math.max(e.m.depthError.p50, floor)}]}))},
    options: {plugins: {title: {display: true, text: 'SAT validation: median time per query against median ' +
                                'depth error (lower left is better)'}},
              scales: {x: {type: 'logarithmic', title: {display: true, text: 'median time per query (ns)'}},
                       y: {type: 'logarithmic', min: floor,
                           title: {display: true, text: 'median depth error (m, 0 drawn at 1e-18)'}}}}});
})();
)";

}  // namespace

std::string SatCheckHtmlSection(const SatCheckSummary& summary) {
  std::ostringstream out;
  out << "<section id=\"sat-check\">\n" << MarkdownToHtml(SatCheckMarkdown(summary));
  out << "<h3>SAT validation: plots</h3>\n<div class=\"plots\" id=\"sat-check-plots\"></div>\n";
  out << "<script type=\"application/json\" id=\"sat-check-data\">" << ScriptSafe(PlotJson(summary).dump())
      << "</script>\n";
  out << "<script>" << kSatScript << "</script>\n</section>\n";
  return out.str();
}

}  // namespace talus::harness
