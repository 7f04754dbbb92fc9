// The report's opening scorecard (docs/testbed-report.md, "Verdicts at a
// glance"): one row per engine and configuration with its truths passed
// out of those judged, its runs fully passing, stopped and failing, the
// FAILs a setting causes (those its "-tuned" configuration removes), how
// often a sweep names it most accurate at equal cost (sweep.h
// CompareFronts, when a sweep is included), and its ms/step on the large
// scenes (bench_summary.h, when they are included); each FAIL is linked to
// its run's section, where its cause is named. Pure functions of their
// inputs, so equal results give equal text.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/report/report.h"

namespace talus::harness {

/// The anchor of a Markdown heading, as GitHub makes it and MarkdownToHtml
/// gives its <h2>/<h3> elements: lower case, letters, digits, '-' and '_'
/// kept, spaces made '-', everything else dropped ("box[mu=0.3]" ->
/// "boxmu03").
std::string HeadingAnchor(std::string_view heading);

/// Each run id's section anchor (its "## <run id>" heading), unique as
/// GitHub makes them: a repeat of an earlier heading's anchor in document
/// order (the title, "Scorecard" and "Overview" come first) gets "-1",
/// "-2"... MarkdownToHtml numbers repeated ids the same way.
std::map<std::string, std::string> RunAnchors(const ResultsFile& file);

/// A run with a FAIL (or that stopped), linked from the scorecard.
struct FailedRun {
  std::string runId;
  std::string anchor;  ///< RunAnchors' anchor of its section
  int fails = 0;       ///< judged metrics outside their tolerance; -1: the run stopped
};

/// One engine and configuration.
struct ScorecardRow {
  std::string backend;
  int judged = 0;        ///< truth metrics with a tolerance (gated or not)
  int passed = 0;        ///< of them, within it
  int runs = 0;          ///< runs made (stopped ones included)
  int runsPassing = 0;   ///< not stopped, and every judged metric passed
  int runsStopped = 0;   ///< stopped with an error
  int settingFails = 0;  ///< judged FAILs that its "-tuned" configuration removes
  /// Runs with at least one FAIL or that stopped, in the results' order.
  std::vector<FailedRun> failRuns;
  int sweepWins = 0;    ///< sweep groups it is most accurate at equal cost in
  int sweepGroups = 0;  ///< sweep groups it is compared in (0: not in the sweep)
  /// Per Scorecard::scenes column: median ms/step, "skipped" or "-".
  std::vector<std::string> sceneCells;
};

struct Scorecard {
  bool hasSweep = false;            ///< ReportExtras::sweep given
  std::vector<std::string> scenes;  ///< large-scene column titles (empty: no scenes)
  /// The main results' backends in order, then any engine only the sweep
  /// or the scenes ran, in first-seen order.
  std::vector<ScorecardRow> rows;
};

/// The scorecard of the results and the extras' sweep and scenes.
Scorecard BuildScorecard(const ResultsFile& file, const ReportExtras& extras);

/// "## Scorecard": the table, then a line on how to read it.
std::string ScorecardMarkdown(const Scorecard& card);

/// report.html's chart of the scorecard: a horizontal bar per backend with
/// its fraction of truths passed, drawn by the page's Chart.js (which must
/// be loaded before this HTML). Empty when no backend has a judged truth.
std::string ScorecardChartHtml(const Scorecard& card);

/// summary.md's pieces before and after the scorecard (report_text.cpp),
/// which report.html separates to place the scorecard's chart: the title
/// and its paragraph; then the overview table, a section per run and the
/// engine settings (the extras' sections not included).
std::string SummaryTitle(const ResultsFile& file);
std::string SummaryRuns(const ResultsFile& file);

/// Markdown bullet lines, one per FAIL (judged metric outside its
/// tolerance) of every backend in `backends` in one run, naming its cause:
/// "a setting" when the backend's "-tuned" counterpart ran the run and
/// passes that metric, "the engine's own behaviour" otherwise, with the
/// tuned error when there is one. Empty when nothing fails.
std::string FailCauseLines(const std::vector<std::string>& backends,
                           const std::map<std::string, const RunResult*>& byBackend);

/// The metric of `r` named `name`, or null.
const MetricResult* FindMetric(const RunResult& r, const std::string& name);

}  // namespace talus::harness
