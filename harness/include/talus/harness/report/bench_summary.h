// The large-scene section of the comparison report: what `talus-scenes`
// measured (talus/harness/scenes/bench_run.h, read back by bench_report_json.h),
// as tables per scene with each engine's time per step against that of
// Bullet's fastest configuration (double or single precision, defaults or
// tuned) from the same invocation, the scaling series as log-log charts of time
// per step against bodies, and the verdict on issue 7's speed goal (Talus
// at most half of Bullet's ms/step on pyramid 15 and hull_pile 10, with
// stability figures no worse).
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
/// The goal: the engine's median ms/step at most this fraction of the peer's.
inline constexpr double kBenchGoalRatio = 0.5;

/// The section as Markdown: "## Large scenes", a table per scene (rows by
/// parameter, then engine in first-seen order, a run on N > 1 threads named
/// "engine, N threads"; skipped runs say why), then "### Thread scaling"
/// and a "where the time goes" table per scene and size when the reports
/// have several thread counts or stage times (src/report/bench_stages.h),
/// then "### Goals": pyramid H = 15 and hull_pile L = 10 when both the goal
/// engine (on one thread) and the peer ran them, and the two-thread
/// speed-up on pyramid H = 20 and hull_pile L = 20. Deterministic for the
/// same reports. Empty for no reports.
std::string BenchMarkdown(const std::vector<BenchReport>& reports);

/// The report scorecard's large-scene figures: one per scene (in the
/// section's order) at its reference size (BenchScene::defaultParameter)
/// when the reports hold it, else at their largest, with each engine's median
/// ms/step on one thread there as the section's table prints it, or "skipped".
struct BenchHeadline {
  std::string title;                                ///< e.g. "pyramid H = 15 (ms/step)"
  std::map<std::string, std::string> cellByEngine;  ///< engines that have a row there
};
std::vector<BenchHeadline> BenchHeadlines(const std::vector<BenchReport>& reports);

/// The section as HTML for report.html: the Markdown's tables plus one
/// log-log chart per scene (median ms/step against dynamic bodies, a line
/// per engine), drawn by the page's Chart.js. Empty for no reports.
std::string BenchHtmlSection(const std::vector<BenchReport>& reports);

}  // namespace talus::harness
