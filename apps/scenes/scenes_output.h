// What talus-scenes writes: one line per finished run on stdout, pushed
// out at once (a series runs for minutes and each line is a finished
// result); progress, skips and repeat summaries on stderr.
#pragma once

#include <string>
#include <vector>

#include "talus/harness/scenes/bench_run.h"

namespace talus::scenes {

/// Writes one line to stdout and flushes it. False, after saying why on
/// stderr, when stdout cannot take it (a full disk, a file that is a
/// directory): the output would be incomplete, so the program stops.
bool PrintLine(const std::string& line);

/// Prints one run's report as a CSV or JSON line (PrintLine).
bool PrintReport(const harness::BenchReport& report, bool csv);

/// The progress a --series run shows on stderr for `label`: every 100th
/// step and the last.
harness::BenchProgress SeriesProgress(const std::string& label);

/// The spread of a perturbed series of repeats on stderr (nothing when
/// there is no summary to give).
void PrintRepeatSummary(const std::vector<harness::BenchReport>& series);

}  // namespace talus::scenes
