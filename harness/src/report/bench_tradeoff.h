// Speed against accuracy on the large scenes: the part of the report's
// "Large scenes" section (bench_summary.h) made from runs of one engine at
// several solver settings (`talus-scenes --iterations 4,8,16 --substeps
// 1,2`). Each run is a point, total wall time against the scene's accuracy
// figure (the pyramid's drift, the hull pile's deepest contact), and an
// engine's front is its runs that no other run of its own beats on both.
// "Faster at equal or better accuracy" is read off these points.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "talus/harness/scenes/bench_run.h"

namespace talus::harness {

/// The runs of one scene size at one thread, in row order, when at least
/// one engine there ran at more than one solver setting; else empty.
struct BenchTradeoff {
  std::string scene;
  int parameter = 0;
  std::vector<const BenchReport*> runs;  ///< made (not skipped), one thread
};
std::vector<BenchTradeoff> BenchTradeoffs(const std::vector<const BenchReport*>& rows);

/// Whether `run` is on its engine's front among `runs`: no other run of the
/// same engine (and steps) has a total time and a figure both no larger and
/// one of them smaller. A run whose figure is missing or NaN is never on it.
bool OnEngineFront(const BenchReport& run, const std::vector<const BenchReport*>& runs);

/// "### Speed against accuracy": per BenchTradeoffs entry, a table of every
/// run (engine, settings, total seconds, mean and longest step, the figure,
/// on its engine's front or not). Empty when there is none.
std::string BenchTradeoffMarkdown(const std::vector<const BenchReport*>& rows);

/// The chart data: per entry, per engine, the (total seconds, figure,
/// settings) points of its runs, sorted by total time.
nlohmann::ordered_json BenchTradeoffChartData(const std::vector<const BenchReport*>& rows);

/// The script drawing one scatter chart per entry into #scenes-tradeoff
/// from #scenes-tradeoff-data (Chart.js, already on the page).
extern const char* const kBenchTradeoffScript;

}  // namespace talus::harness
