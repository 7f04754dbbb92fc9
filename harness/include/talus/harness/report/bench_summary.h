// The large-scene section of the comparison report: what `talus-scenes`
// measured (talus/harness/scenes/bench_run.h, read back by bench_report_json.h),
// as tables per scene with each run's cost (total wall time, mean and
// longest step) against that of Bullet's fastest configuration (double or
// single precision, defaults or tuned) from the same invocation, the
// scaling series as log-log charts of mean time per step against bodies,
// and the verdict on the speed goal (Talus at most half of Bullet's total
// time on pyramid 15 and hull_pile 10, with stability figures no worse).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "talus/harness/scenes/bench_run.h"

namespace talus::harness {

/// Bullet's backend name: every ratio of the section divides by the fastest
/// of this backend and its configurations ("bullet-tuned", "bullet-f32"...).
inline constexpr const char* kBenchRatioPeer = "bullet";
/// The engine whose goal the section judges.
inline constexpr const char* kBenchGoalEngine = "talus";
/// The goal: the engine's total time at most this fraction of the peer's.
inline constexpr double kBenchGoalRatio = 0.5;

/// The section as Markdown: "## Large scenes", a table per scene (rows by
/// parameter, then engine in first-seen order, a run on N > 1 threads named
/// "engine, N threads", one with other solver settings named with them
/// (BenchRunLabel); skipped runs say why; ratios by total time against the
/// fastest Bullet at its defaults over the same steps), then "### Speed
/// against accuracy" when an engine ran at several solver settings
/// (src/report/bench_tradeoff.h), "### Thread scaling"
/// and a "where the time goes" table per scene and size when the reports
/// have several thread counts or stage times (src/report/bench_stages.h),
/// then "### Goals": pyramid H = 15 and hull_pile L = 10 when both the goal
/// engine and the peer ran them at their defaults, and the two-thread
/// speed-up on pyramid H = 20 and hull_pile L = 20. Deterministic for the
/// same reports. Empty for no reports.
std::string BenchMarkdown(const std::vector<BenchReport>& reports);

/// The report scorecard's large-scene figures: one per scene (in the
/// section's order) at its reference size (BenchScene::defaultParameter)
/// when the reports hold it, else at their largest, with each engine's mean
/// ms/step (total / steps) at its defaults on one thread there, or "skipped".
struct BenchHeadline {
  std::string title;                                ///< e.g. "pyramid H = 15 (mean ms/step)"
  std::map<std::string, std::string> cellByEngine;  ///< engines that have a row there
};
std::vector<BenchHeadline> BenchHeadlines(const std::vector<BenchReport>& reports);

/// The section as HTML for report.html: the Markdown's tables plus one
/// log-log chart per scene (mean ms/step against dynamic bodies, a line
/// per engine), and the speed-against-accuracy charts (total time against
/// drift or penetration, a line per engine over its settings), drawn by the
/// page's Chart.js. Empty for no reports.
std::string BenchHtmlSection(const std::vector<BenchReport>& reports);

}  // namespace talus::harness
