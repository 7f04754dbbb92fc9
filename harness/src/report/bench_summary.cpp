// The large-scene section of the report (talus/harness/report/bench_summary.h).
//
// Rows are grouped by scene (in BenchScenes() order, unknown scenes after,
// by name), then parameter ascending, then engine in the order the reports
// first name it, so the same reports always give the same text. The cost is
// the run's total wall time (docs/bench-scenes.md, "Cost"): ratios divide
// one run's total by that of Bullet's fastest configuration at its defaults
// with the same number of steps in the same file (any of "bullet",
// "bullet-tuned", "bullet-f32", "bullet-f32-tuned" that ran): talus-scenes
// runs every engine in one invocation, so they were measured on the same
// machine at the same moment.
#include "talus/harness/report/bench_summary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "report/bench_stages.h"
#include "report/bench_tradeoff.h"
#include "report/markdown_html.h"
#include "support/text_util.h"
#include "talus/harness/scenes/bench_scenes.h"

namespace talus::harness {
namespace {

// One scene's reports, in row order.
struct SceneRows {
  std::string scene;
  std::vector<const BenchReport*> rows;
};

int SceneOrder(const std::string& scene) {
  const auto& scenes = BenchScenes();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    if (scenes[i].name == scene) return static_cast<int>(i);
  }
  return static_cast<int>(scenes.size());
}

std::vector<SceneRows> GroupByScene(const std::vector<BenchReport>& reports) {
  std::vector<std::string> engines;  // first-seen order
  for (const BenchReport& r : reports) {
    if (std::find(engines.begin(), engines.end(), r.engine) == engines.end()) engines.push_back(r.engine);
  }
  const auto engineRank = [&](const std::string& e) {
    return std::find(engines.begin(), engines.end(), e) - engines.begin();
  };
  std::vector<const BenchReport*> sorted;
  for (const BenchReport& r : reports) sorted.push_back(&r);
  std::stable_sort(sorted.begin(), sorted.end(), [&](const BenchReport* a, const BenchReport* b) {
    const int sa = SceneOrder(a->scene), sb = SceneOrder(b->scene);
    if (sa != sb) return sa < sb;
    if (a->scene != b->scene) return a->scene < b->scene;
    if (a->parameter != b->parameter) return a->parameter < b->parameter;
    return engineRank(a->engine) < engineRank(b->engine);
  });
  std::vector<SceneRows> groups;
  for (const BenchReport* r : sorted) {
    if (groups.empty() || groups.back().scene != r->scene) groups.push_back({r->scene, {}});
    groups.back().rows.push_back(r);
  }
  return groups;
}

// A run at the engine's defaults: one thread, its own iteration count, one
// substep (the goals and the ratios judge engines as their users get them).
bool AtDefaults(const BenchReport& r) {
  return r.threads == 1 && r.solver.iterations == 0 && r.solver.substeps == 1 && r.skipped.empty();
}

const BenchReport* Find(const std::vector<BenchReport>& reports, const std::string& engine,
                        const std::string& scene, int parameter) {
  for (const BenchReport& r : reports) {
    if (r.engine == engine && r.scene == scene && r.parameter == parameter && AtDefaults(r)) return &r;
  }
  return nullptr;
}

// The fastest run (least total time) of the peer's configurations
// (kBenchRatioPeer or a name starting with it and '-') at their defaults on
// this scene, parameter and number of steps; null if none ran.
const BenchReport* FastestPeer(const std::vector<BenchReport>& reports, const std::string& scene,
                               int parameter, int steps) {
  const std::string peer = kBenchRatioPeer;
  const BenchReport* fastest = nullptr;
  for (const BenchReport& r : reports) {
    const bool isPeer = r.engine == peer || r.engine.rfind(peer + "-", 0) == 0;
    if (!isPeer || r.scene != scene || r.parameter != parameter || r.steps != steps || !AtDefaults(r) ||
        !(r.totalMs > 0.0)) {
      continue;
    }
    if (fastest == nullptr || r.totalMs < fastest->totalMs) fastest = &r;
  }
  return fastest;
}

std::string Figure(const std::optional<double>& value) {
  return value ? FormatNumber(*value, 3) : std::string("-");
}

std::string ParameterName(const std::string& scene) {
  const BenchScene* known = FindBenchScene(scene);
  return known ? std::string(known->parameterName) : std::string("parameter");
}

void WriteTable(std::ostringstream& out, const SceneRows& group, const std::vector<BenchReport>& reports) {
  const bool pyramid = group.scene == "pyramid";
  out << "\n### " << group.scene << "\n\n| " << ParameterName(group.scene)
      << " | bodies | engine | steps | total (s) | ms/step (mean) | longest step (ms) | / fastest "
      << kBenchRatioPeer << " (total) | max contacts | "
      << (pyramid ? "drift (m)" : "max penetration (m) | kinetic energy (J) | escaped")
      << " |\n|---|---|---|---|---|---|---|---|---|" << (pyramid ? "---|" : "---|---|---|") << "\n";
  for (const BenchReport* r : group.rows) {
    out << "| " << r->parameter << " | " << r->bodies << " | " << BenchRunLabel(*r) << " | " << r->steps
        << " | ";
    if (!r->skipped.empty()) {
      out << "skipped: " << r->skipped << " |\n";
      continue;
    }
    const BenchReport* peer = FastestPeer(reports, r->scene, r->parameter, r->steps);
    const std::string ratio =
        peer != nullptr ? Concat({FormatNumber(r->totalMs / peer->totalMs, 3), " (", peer->engine, ")"})
                        : "-";
    out << FormatNumber(r->totalMs / 1e3, 4) << " | " << FormatNumber(r->msMean, 4) << " | "
        << FormatNumber(r->msMax, 4) << " | " << ratio << " | " << r->maxContacts << " | ";
    if (pyramid) {
      out << Figure(r->drift) << " |\n";
    } else {
      out << Figure(r->maxPenetration) << " | " << Figure(r->kineticEnergy) << " | "
          << (r->escaped ? std::to_string(*r->escaped) : "-") << " |\n";
    }
  }
}

// "a (engine) vs b (peer): no worse" for one stability figure, where
// smaller is better.
std::string Compare(const char* name, const std::optional<double>& ours, const std::optional<double>& peer,
                    const char* unit) {
  if (!ours || !peer) return "";
  const bool noWorse = *ours <= *peer;
  return Concat({"; ", name, " ", FormatNumber(*ours, 3), unit, " vs ", FormatNumber(*peer, 3), unit, " (",
                 noWorse ? "no worse" : "worse", ")"});
}

void WriteGoals(std::ostringstream& out, const std::vector<BenchReport>& reports,
                const std::vector<const BenchReport*>& rows) {
  std::ostringstream goals;
  for (const auto& [scene, parameter] : {std::pair<std::string, int>{"pyramid", 15}, {"hull_pile", 10}}) {
    const BenchReport* ours = Find(reports, kBenchGoalEngine, scene, parameter);
    if (ours == nullptr) continue;
    const BenchReport* peer = FastestPeer(reports, scene, parameter, ours->steps);
    if (peer == nullptr) continue;
    const double ratio = ours->totalMs / peer->totalMs;
    goals << "- " << scene << " " << ParameterName(scene) << " = " << parameter << ": " << kBenchGoalEngine
          << " / " << peer->engine << " (the fastest " << kBenchRatioPeer << "), total time over "
          << ours->steps << " steps = " << FormatNumber(ratio, 3)
          << " (goal <= " << FormatNumber(kBenchGoalRatio) << ": "
          << (ratio <= kBenchGoalRatio ? "met" : "missed") << ")"
          << Compare("drift", ours->drift, peer->drift, " m")
          << Compare("max penetration", ours->maxPenetration, peer->maxPenetration, " m")
          << Compare("kinetic energy", ours->kineticEnergy, peer->kineticEnergy, " J");
    if (ours->escaped && peer->escaped) {
      goals << "; escaped " << *ours->escaped << " vs " << *peer->escaped << " ("
            << (*ours->escaped <= *peer->escaped ? "no worse" : "worse") << ")";
    }
    goals << "\n";
  }
  goals << BenchThreadGoals(rows);
  if (goals.str().empty()) return;
  out << "\n### Goals\n\n" << goals.str();
}

// Chart data: per scene, per engine, the (bodies, mean ms/step) points of
// the runs made.
nlohmann::ordered_json ChartData(const std::vector<SceneRows>& groups) {
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const SceneRows& group : groups) {
    std::vector<std::string> engines;
    std::map<std::string, nlohmann::ordered_json> points;
    for (const BenchReport* r : group.rows) {
      if (!r->skipped.empty() || !std::isfinite(r->msMean)) continue;
      const std::string label = BenchRunLabel(*r);
      if (!points.count(label)) engines.push_back(label);
      points[label].push_back({{"bodies", r->bodies}, {"parameter", r->parameter}, {"ms", r->msMean}});
    }
    nlohmann::ordered_json lines = nlohmann::ordered_json::array();
    for (const std::string& e : engines) lines.push_back({{"engine", e}, {"points", points[e]}});
    scenes.push_back(
        {{"scene", group.scene}, {"parameterName", ParameterName(group.scene)}, {"lines", lines}});
  }
  return scenes;
}

// One log-log chart per scene: mean ms/step (total / steps) against dynamic bodies.
constexpr const char* kScalingScript = R"(
(function() {
  const scenes = JSON.parse(document.getElementById('scenes-data').textContent);
  const section = document.getElementById('scenes-plots');
  const palette = ['#1f77b4','#d62728','#2ca02c','#ff7f0e','#9467bd','#8c564b','#e377c2','#7f7f7f'];
  for (const scene of scenes) {
    if (!scene.lines.length) continue;
    const box = document.createElement('div'); box.className = 'plot';
    const canvas = document.createElement('canvas'); box.appendChild(canvas); section.appendChild(box);
    const datasets = scene.lines.map((line, k) => ({label: line.engine, showLine: true,
      borderColor: palette[k % palette.length], backgroundColor: palette[k % palette.length],
      data: line.points.map(p => ({x: p.bodies, y: p.ms, p: p.parameter}))}));
    new Chart(canvas, {type: 'scatter', data: {datasets: datasets}, options: {animation: false,
      maintainAspectRatio: false,
      plugins: {title: {display: true, text: scene.scene + ': time per step against bodies'},
                tooltip: {callbacks: {label: c => c.dataset.label + ' ' + scene.parameterName + '=' + c.raw.p +
                  ': ' + c.raw.x + ' bodies, ' + c.raw.y.toPrecision(3) + ' ms/step'}}},
      scales: {x: {type: 'logarithmic', title: {display: true, text: 'dynamic bodies'}},
               y: {type: 'logarithmic', title: {display: true, text: 'mean ms/step (total / steps)'}}}}});
  }
})();
)";

}  // namespace

std::string BenchMarkdown(const std::vector<BenchReport>& reports) {
  if (reports.empty()) return "";
  const std::vector<SceneRows> groups = GroupByScene(reports);
  std::vector<const BenchReport*> rows;
  for (const SceneRows& group : groups) rows.insert(rows.end(), group.rows.begin(), group.rows.end());
  const std::string stages = BenchStagesMarkdown(rows);
  const std::string threads = BenchThreadsMarkdown(rows);
  const std::string tradeoff = BenchTradeoffMarkdown(rows);
  std::ostringstream out;
  out << "## Large scenes\n\nThe reference scenes of docs/bench-scenes.md (talus-scenes). The cost is the "
         "run's total wall time (its mean step is total / steps), with the longest step beside it; each "
         "run's total is divided by that of "
      << kBenchRatioPeer
      << "'s fastest configuration at its defaults (named in brackets) over the same steps from the same "
         "invocation. An engine run on more than one thread is named with its thread count, every other "
         "on one; one run with other solver settings is named with them (iterations, substeps).";
  if (!tradeoff.empty())
    out << " [Speed against accuracy](#speed-against-accuracy) sets each engine's settings side by side.";
  if (!threads.empty()) out << " [Thread scaling](#thread-scaling) compares an engine's thread counts.";
  if (!stages.empty())
    out << " For an engine that times its stages, a table per size says [where the time "
           "goes](#where-the-time-goes).";
  out << "\n";
  for (const SceneRows& group : groups) WriteTable(out, group, reports);
  out << tradeoff << threads << stages;
  WriteGoals(out, reports, rows);
  return out.str();
}

std::vector<BenchHeadline> BenchHeadlines(const std::vector<BenchReport>& reports) {
  std::vector<BenchHeadline> headlines;
  for (const SceneRows& group : GroupByScene(reports)) {
    // The scene's reference size (the goals' H = 15, L = 10) when it was
    // run; else the largest (rows are sorted by parameter).
    const BenchScene* known = FindBenchScene(group.scene);
    int parameter = group.rows.back()->parameter;
    for (const BenchReport* r : group.rows) {
      if (known != nullptr && r->parameter == known->defaultParameter) parameter = r->parameter;
    }
    BenchHeadline headline;
    headline.title = Concat(
        {group.scene, " ", ParameterName(group.scene), " = ", std::to_string(parameter), " (mean ms/step)"});
    for (const BenchReport* r : group.rows) {
      // At the defaults: the scorecard's rows are engines, and the goals
      // judge one thread at each engine's own settings.
      if (r->parameter != parameter || r->threads != 1 || r->solver.iterations != 0 ||
          r->solver.substeps != 1)
        continue;
      if (!r->skipped.empty()) {
        headline.cellByEngine[r->engine] = "skipped";
        continue;
      }
      headline.cellByEngine[r->engine] = FormatNumber(r->msMean, 4);
    }
    headlines.push_back(std::move(headline));
  }
  return headlines;
}

std::string BenchHtmlSection(const std::vector<BenchReport>& reports) {
  if (reports.empty()) return "";
  std::ostringstream out;
  out << MarkdownToHtml(BenchMarkdown(reports));
  out << "<div class=\"plots\" id=\"scenes-plots\"></div>\n";
  out << "<script type=\"application/json\" id=\"scenes-data\">"
      << ScriptSafe(ChartData(GroupByScene(reports)).dump()) << "</script>\n";
  out << "<script>" << kScalingScript << "</script>\n";
  const std::vector<SceneRows> groups = GroupByScene(reports);
  std::vector<const BenchReport*> rows;
  for (const SceneRows& group : groups) rows.insert(rows.end(), group.rows.begin(), group.rows.end());
  const nlohmann::ordered_json tradeoff = BenchTradeoffChartData(rows);
  if (!tradeoff.empty()) {
    out << "<div class=\"plots\" id=\"scenes-tradeoff\"></div>\n";
    out << "<script type=\"application/json\" id=\"scenes-tradeoff-data\">" << ScriptSafe(tradeoff.dump())
        << "</script>\n";
    out << "<script>" << kBenchTradeoffScript << "</script>\n";
  }
  return out.str();
}

}  // namespace talus::harness
