// The comparison report of a testbed run, from its results:
//   summary.md    per run: the truths, each engine's error against them and
//                 its time per step, pass/fail against the file's
//                 tolerances; then each engine's settings
//   results.csv   one row per (run, backend, metric), every number
//   results.json  the results file itself, with its trajectory file
//                 (results_file.h)
//   report.html   the tables plus plots (heights and energy over time per
//                 run, time per step per engine), self-contained but for
//                 report-data.js beside it (the plots' series and the
//                 replays, kReportDataFile): the charting library (Chart.js, from
//                 harness/report's npm lock) is inlined, so it opens from
//                 disk with no network; with three.js inlined too, the 3D
//                 replay of runs recorded with --replay, the Quickhull
//                 trace and the broad-phase funnel
//                 (docs/testbed-report.md); with the extras
//                 (ReportExtras), the SAT validation, a separate sweep's
//                 run-time-against-error charts, the stability envelope
//                 and the large scenes with their scaling charts, so one
//                 page holds every analysis
// All text is deterministic for deterministic results.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include <vector>

#include "talus/harness/report/sat_check_results.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/scenes/bench_run.h"
#include "talus/harness/stress/stress.h"
#include "talus/result.h"

namespace talus::harness {

/// The files beside report.html that hold the plots' series and the
/// replays' frames (most of a report's bytes), which the page loads with
/// a <script src> (a page opened from disk may load a script beside it,
/// but not fetch a JSON file). Two files, as their sizes grow with two
/// different things: the plots with the runs, the replays with the runs
/// recorded for replay (docs/testbed-report.md "Sizes").
inline constexpr std::string_view kReportDataFile = "report-data.js";
inline constexpr std::string_view kReportReplayFile = "report-replay.js";

/// The analyses a report can add after the run's own sections, each read
/// from its own program's output; a null pointer leaves its section out.
/// The pointees must outlive the call.
struct ReportExtras {
  /// talus-sat-check --json: "SAT validation" (tables and plots).
  const SatCheckSummary* satCheck = nullptr;
  /// A `talus-testbed sweep` results file: "Run time against error" (the
  /// main results file's own sweep, if it is one, is shown regardless).
  const ResultsFile* sweep = nullptr;
  /// `talus-testbed stress` envelopes: "Stability envelope".
  const std::vector<StressEntry>* stress = nullptr;
  /// `talus-scenes --format jsonl` lines: "Large scenes" (tables, goals,
  /// scaling charts).
  const std::vector<BenchReport>* scenes = nullptr;
};

/// The overview table (Markdown): one row per checked truth metric and run,
/// a column per backend with its error and ok/FAIL, and a last row of
/// median times per step. What `run` and `report` print; summary.md's
/// copy has `linkFails` set, so each FAIL links to its run's section
/// ("[FAIL](#anchor)", report_scorecard.h HeadingAnchor).
std::string OverviewTable(const ResultsFile& file, bool linkFails = false);

/// summary.md's text: the scorecard first (one row per engine and
/// configuration, with the sweep's and the large scenes' columns when
/// those extras are given), then the overview table and the run sections;
/// each extra that is given appends its section (in the order SAT
/// validation, run time against error, stability envelope, large scenes).
std::string SummaryMarkdown(const ResultsFile& file, const ReportExtras& extras = {});

/// results.csv's text (RFC 4180 quoting, header row first).
std::string ResultsCsv(const ResultsFile& file);

/// report.html's text; `chartLibrary` is the charting library's JavaScript
/// and `threeLibrary` three.js's (empty: the 3D views say it is missing),
/// each inlined into a <script> element; the extras' sections and their
/// plots are added at the end, in the order of SummaryMarkdown.
std::string ReportHtml(const ResultsFile& file, std::string_view chartLibrary,
                       std::string_view threeLibrary = {}, const ReportExtras& extras = {});

/// kReportDataFile's text: a script setting window.talusReportData to
/// {"plots": the series per run and backend, in the display form of
/// display_trajectory.h}.
std::string ReportDataScript(const ResultsFile& file);

/// kReportReplayFile's text: a script setting window.talusReportReplays to
/// the replays as report_html_replay.h's ReplayRunsForPage gives them.
std::string ReportReplayScript(const ResultsFile& file);

/// Writes summary.md, results.csv, results.json (and its trajectory file),
/// report.html, kReportDataFile and kReportReplayFile into `folder` (created if missing), as
/// one set: all of them or, on any failure, none (WriteFilesAtomically).
/// Reads the charting library from `chartLibraryPath` and three.js from
/// `threeLibraryPath` (empty: none); errors name the file. The extras add
/// their sections to summary.md and report.html.
Result<std::monostate> WriteReport(const ResultsFile& file, const std::filesystem::path& folder,
                                   const std::filesystem::path& chartLibraryPath,
                                   const std::filesystem::path& threeLibraryPath = {},
                                   const ReportExtras& extras = {});

}  // namespace talus::harness
