// The sweep analysis (sweep_analysis.h) written out: sweep.json and the
// Markdown section of sweep.md and summary.md; the report.html section is
// drawn by the report (harness/src/report/report_html_sweeps.cpp).
#pragma once

#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/sweep_analysis.h"

namespace talus::harness {

/// The analysis as JSON (2-space indented, infinities as null) and as a
/// Markdown section (per group: the winner, wins, error at the matched
/// cost; the family tallies; per group each family pair's verdict; each
/// backend's front with cost and longest step).
std::string SweepToJson(const std::vector<SweepGroup>& groups);
std::string SweepMarkdown(const std::vector<SweepGroup>& groups);

/// The report.html section of a results file holding a stepping sweep
/// (runs with "h" sweep values): log-log charts, one per group, one
/// dataset per curve, fronts drawn as dashed lines. Empty when there is no
/// sweep. Uses the page's Chart.js.
std::string SweepHtmlSection(const ResultsFile& file);

}  // namespace talus::harness
