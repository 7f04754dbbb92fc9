// Where a large-scene step's time goes and how it scales with threads: the
// parts of the report's "Large scenes" section (bench_summary.h) made from
// BenchReport::stages and BenchReport::threads, as talus-scenes measured
// them (`--threads 1,2` runs each Talus engine at both counts back to back).
#pragma once

#include <string>
#include <vector>

#include "talus/harness/scenes/bench_run.h"

namespace talus::harness {

/// Two threads must step at least this many times faster than one
/// (issue 12, "Two threads"), judged on pyramid H = 20 and hull_pile L = 20.
inline constexpr double kBenchThreadGoalSpeedup = 1.7;

/// How the section names a run: the engine, with ", N threads" when it
/// stepped on more than one and its solver settings when they are not the
/// engine's defaults ("talus-coloured, 2 threads", "bullet, 20 iterations,
/// 2 substeps").
std::string BenchRunLabel(const BenchReport& report);

/// "### <scene> <P> = <p>: where the time goes" for each scene and size
/// with a run that timed its stages (`rows` in the section's row order):
/// one row per stage (in the engine's order) and one column per such run,
/// each cell the stage's mean ms/step, its share of the run's total time
/// (stage mean / step mean) and its longest step; an "other" row for the
/// time outside the stages (the backend's own work), a "step" row with the
/// mean and longest step; and, for an engine run at one and at N threads,
/// a column of each stage's speed-up (1-thread mean / N-thread mean), which
/// shows the stages that do not run on the pool.
/// Empty when no run has stages.
std::string BenchStagesMarkdown(const std::vector<const BenchReport*>& rows);

/// "### Thread scaling": for each scene, size and engine run at more than
/// one thread count, its mean ms/step (total / steps) at each count and the
/// speed-up (ratio of the totals) over its 1-thread run from the same file. Empty when no engine ran at two
/// counts.
std::string BenchThreadsMarkdown(const std::vector<const BenchReport*>& rows);

/// The "Two threads" goal lines ("- pyramid H = 20: talus-coloured at 1 /
/// 2 threads = 1.8 (goal >= 1.7: met)"), one per engine with both runs at
/// pyramid H = 20 or hull_pile L = 20; empty when there are none.
std::string BenchThreadGoals(const std::vector<const BenchReport*>& rows);

/// Whether two runs used the same solver settings (iterations and
/// sub-steps): the stage and trade-off tables compare like with like.
bool SameSolver(const BenchReport* a, const BenchReport* b);

}  // namespace talus::harness
