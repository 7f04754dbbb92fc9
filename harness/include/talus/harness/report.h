// The comparison report of a testbed run, from its results:
//   summary.md    per run: the truths, each engine's error against them and
//                 its time per step, pass/fail against the file's
//                 tolerances; then each engine's settings
//   results.csv   one row per (run, backend, metric), every number
//   results.json  the results file itself (results_file.h)
//   report.html   the tables plus plots (heights and energy over time per
//                 run, time per step per engine), self-contained: the
//                 charting library (Chart.js, from harness/report's npm
//                 lock) is inlined, so it opens from disk with no network;
//                 with three.js inlined too, the 3D replay of runs recorded
//                 with --replay, the Quickhull trace and the broad-phase
//                 funnel (docs/testbed-report.md); with talus-sat-check's
//                 results, the SAT validation section and its plots
// All text is deterministic for deterministic results.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include "talus/harness/results_file.h"
#include "talus/harness/sat_check_results.h"
#include "talus/result.h"

namespace talus::harness {

/// The overview table (Markdown): one row per checked truth metric and run,
/// a column per backend with its error and ok/FAIL, and a last row of
/// median times per step. What `run` and `report` print.
std::string OverviewTable(const ResultsFile& file);

/// summary.md's text; with `satCheck` (talus-sat-check's results, may be
/// null) the section "SAT validation" is appended.
std::string SummaryMarkdown(const ResultsFile& file, const SatCheckSummary* satCheck = nullptr);

/// results.csv's text (RFC 4180 quoting, header row first).
std::string ResultsCsv(const ResultsFile& file);

/// report.html's text; `chartLibrary` is the charting library's JavaScript
/// and `threeLibrary` three.js's (empty: the 3D views say it is missing),
/// each inlined into a <script> element; with `satCheck` (may be null) the
/// SAT validation section and its plots are added at the end.
std::string ReportHtml(const ResultsFile& file, std::string_view chartLibrary,
                       std::string_view threeLibrary = {}, const SatCheckSummary* satCheck = nullptr);

/// Writes the four files into `folder` (created if missing), reading the
/// charting library from `chartLibraryPath` and three.js from
/// `threeLibraryPath` (empty: none); errors name the file. `satCheck` (may
/// be null) adds the SAT validation section to summary.md and report.html.
Result<std::monostate> WriteReport(const ResultsFile& file, const std::filesystem::path& folder,
                                   const std::filesystem::path& chartLibraryPath,
                                   const std::filesystem::path& threeLibraryPath = {},
                                   const SatCheckSummary* satCheck = nullptr);

}  // namespace talus::harness
