// Speed against accuracy on the large scenes (bench_tradeoff.h).
//
// Only one-thread runs count: the thread count is its own axis (the thread
// scaling table), and a point should differ from its neighbours by the
// solver settings alone. Every figure comes from one talus-scenes file, so
// the total times compare runs of the same invocation.
#include "report/bench_tradeoff.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/bench_stages.h"
#include "support/text_util.h"
#include "talus/harness/scenes/bench_perturb.h"
#include "talus/harness/scenes/bench_scenes.h"

namespace talus::harness {
namespace {

// The accuracy figure of a run, NaN when it has none.
double FigureOf(const BenchReport& r) { return BenchVerdictFigure(r).value_or(std::nan("")); }

std::string FigureName(const std::string& scene) {
  return scene == "pyramid" ? "drift (m)" : "max penetration (m)";
}

std::string SizeTitle(const std::string& scene, int parameter) {
  const BenchScene* known = FindBenchScene(scene);
  const std::string name = known ? std::string(known->parameterName) : std::string("parameter");
  return Concat({scene, " ", name, " = ", std::to_string(parameter)});
}

}  // namespace

std::vector<BenchTradeoff> BenchTradeoffs(const std::vector<const BenchReport*>& rows) {
  std::vector<BenchTradeoff> sizes;
  for (const BenchReport* r : rows) {
    if (!r->skipped.empty() || r->threads != 1) continue;
    if (sizes.empty() || sizes.back().scene != r->scene || sizes.back().parameter != r->parameter) {
      sizes.push_back({r->scene, r->parameter, {}});
    }
    sizes.back().runs.push_back(r);
  }
  std::vector<BenchTradeoff> kept;
  for (BenchTradeoff& size : sizes) {
    const bool several = std::any_of(size.runs.begin(), size.runs.end(), [&size](const BenchReport* a) {
      return std::any_of(size.runs.begin(), size.runs.end(),
                         [a](const BenchReport* b) { return a->engine == b->engine && !SameSolver(a, b); });
    });
    if (several) kept.push_back(std::move(size));
  }
  return kept;
}

bool OnEngineFront(const BenchReport& run, const std::vector<const BenchReport*>& runs) {
  const double figure = FigureOf(run);
  if (std::isnan(figure)) return false;
  for (const BenchReport* other : runs) {
    if (other == &run || other->engine != run.engine || other->steps != run.steps) continue;
    const double otherFigure = FigureOf(*other);
    if (std::isnan(otherFigure)) continue;
    const bool noWorse = other->totalMs <= run.totalMs && otherFigure <= figure;
    const bool better = other->totalMs < run.totalMs || otherFigure < figure;
    if (noWorse && better) return false;
  }
  return true;
}

std::string BenchTradeoffMarkdown(const std::vector<const BenchReport*>& rows) {
  const std::vector<BenchTradeoff> sizes = BenchTradeoffs(rows);
  if (sizes.empty()) return "";
  std::ostringstream out;
  out << "\n### Speed against accuracy\n\nEach engine over its solver settings (talus-scenes --iterations, "
         "--substeps; \"engine default\" is the engine's own), one thread: the run's total wall time "
         "against the scene's accuracy figure. A run is on its engine's front when no other run of the same "
         "engine is both no slower and no less accurate (and better in one). \"Faster at equal or better "
         "accuracy\" compares fronts.\n";
  for (const BenchTradeoff& size : sizes) {
    out << "\n### " << SizeTitle(size.scene, size.parameter)
        << ": speed against accuracy\n\n| engine | settings | steps | total (s) | "
        << "ms/step (mean) | longest step (ms) | " << FigureName(size.scene)
        << " | on its front |\n|---|---|---|---|---|---|---|---|\n";
    for (const BenchReport* r : size.runs) {
      const double figure = FigureOf(*r);
      out << "| " << r->engine << " | " << BenchSolverLabel(r->solver) << " | " << r->steps << " | "
          << FormatNumber(r->totalMs / 1e3, 4) << " | " << FormatNumber(r->msMean, 4) << " | "
          << FormatNumber(r->msMax, 4) << " | "
          << (std::isnan(figure) ? std::string("-") : FormatNumber(figure, 3)) << " | "
          << (OnEngineFront(*r, size.runs) ? "yes" : "no") << " |\n";
    }
  }
  return out.str();
}

nlohmann::ordered_json BenchTradeoffChartData(const std::vector<const BenchReport*>& rows) {
  nlohmann::ordered_json charts = nlohmann::ordered_json::array();
  for (const BenchTradeoff& size : BenchTradeoffs(rows)) {
    std::vector<std::string> engines;  // first-seen order
    for (const BenchReport* r : size.runs) {
      if (std::find(engines.begin(), engines.end(), r->engine) == engines.end()) engines.push_back(r->engine);
    }
    nlohmann::ordered_json lines = nlohmann::ordered_json::array();
    for (const std::string& engine : engines) {
      std::vector<const BenchReport*> runs;
      for (const BenchReport* r : size.runs) {
        if (r->engine == engine && std::isfinite(FigureOf(*r))) runs.push_back(r);
      }
      std::stable_sort(runs.begin(), runs.end(),
                       [](const BenchReport* a, const BenchReport* b) { return a->totalMs < b->totalMs; });
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const BenchReport* r : runs) {
        points.push_back({{"seconds", r->totalMs / 1e3},
                          {"figure", FigureOf(*r)},
                          {"settings", BenchSolverLabel(r->solver)}});
      }
      lines.push_back({{"engine", engine}, {"points", points}});
    }
    charts.push_back({{"title", SizeTitle(size.scene, size.parameter)},
                      {"figure", FigureName(size.scene)},
                      {"lines", lines}});
  }
  return charts;
}

const char* const kBenchTradeoffScript = R"(
(function() {
  const charts = JSON.parse(document.getElementById('scenes-tradeoff-data').textContent);
  const section = document.getElementById('scenes-tradeoff');
  const palette = ['#1f77b4','#d62728','#2ca02c','#ff7f0e','#9467bd','#8c564b','#e377c2','#7f7f7f'];
  for (const chart of charts) {
    const box = document.createElement('div'); box.className = 'plot';
    const canvas = document.createElement('canvas'); box.appendChild(canvas); section.appendChild(box);
    const datasets = chart.lines.map((line, k) => ({label: line.engine, showLine: true,
      borderColor: palette[k % palette.length], backgroundColor: palette[k % palette.length],
      data: line.points.map(p => ({x: p.seconds, y: p.figure, s: p.settings}))}));
    new Chart(canvas, {type: 'scatter', data: {datasets: datasets}, options: {animation: false,
      maintainAspectRatio: false,
      plugins: {title: {display: true, text: chart.title + ': total time against ' + chart.figure},
                tooltip: {callbacks: {label: c => c.dataset.label + ' (' + c.raw.s + '): ' +
                  c.raw.x.toPrecision(3) + ' s, ' + c.raw.y.toPrecision(3)}}},
      scales: {x: {title: {display: true, text: 'total wall time (s)'}},
               y: {title: {display: true, text: chart.figure}}}}});
  }
})();
)";

}  // namespace talus::harness
