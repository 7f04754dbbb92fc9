// The results file of a testbed run (results.json): every RunResult with
// its metrics, settings, timings and plot series, in the runner's order;
// each backend's settings and each run's metric definitions are written
// once, in tables the results name (results_tables.h in harness/src/run).
// Schema in docs/testbed-runner.md. NaN numbers (nothing measured, no
// integrator answer) are written as null and read back as NaN. Writing is
// deterministic: fixed key order, numbers in shortest round-trip form, so
// equal results give byte-identical files.
//
// On disk the file is three: results.json holds everything but each
// result's trajectory; "results.trajectories.json" beside it
// (TrajectoryFilePath) holds the plot series, one line per result; and
// "results.replays.json" (ReplayFilePath) the replays of the runs recorded
// with --replay (poses, contacts and counters of every frame), one line
// each. The trajectories are most of a run's bytes (the default report's
// results.json was 65 MB with them, docs/testbed-report.md "Sizes"), and
// only the report's plots and replay read them; the series grow with the
// runs, the replays with the runs replayed, so each has its file. The
// three are written as one set (WriteFilesAtomically) and read back
// together; by default the trajectories are in the display form
// (display_trajectory.h).
// ResultsToJson is the one-text form with the trajectories inside each
// result (the form shard files embed, and how results.json was written
// before the split); the readers take both forms.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "talus/harness/run/runner.h"
#include "talus/harness/support/atomic_file.h"
#include "talus/result.h"

namespace talus::harness {

/// The file's "format" value, checked on reading.
inline constexpr std::string_view kResultsFormat = "talus-testbed-results";
/// The file's "version" value, checked on reading. 2: each backend's
/// settings and each run's metric definitions in tables at the top, named by
/// the results (results_tables.h); a file of version 1 repeated them in
/// every result and is refused with the version this build expects.
inline constexpr int kResultsVersion = 2;

/// A whole run of the testbed.
struct ResultsFile {
  std::vector<std::string> backends;  ///< as asked, in order
  bool deterministic = false;         ///< wall times were zeroed
  std::vector<RunResult> results;     ///< runs x backends, run-major
  /// Whether the trajectory file keeps the trajectories exact (`run
  /// --full-trajectories`; its "resolution": "full") rather than in the
  /// display form of display_trajectory.h (the default, "display"). Read
  /// back from the file, so a report rewriting it keeps its form; files
  /// written before the display form were exact and read as full.
  bool fullTrajectories = false;
  /// Set when the trajectories were read from a display-form file: they
  /// are written (and drawn) as they are, since rounding them again to
  /// their own range could move a value by one step.
  bool trajectoriesInDisplayForm = false;
};

/// The trajectory file's "format" and "version" values, checked on reading.
inline constexpr std::string_view kTrajectoriesFormat = "talus-testbed-trajectories";
inline constexpr int kTrajectoriesVersion = 1;
/// The replay file's "format" and "version" values, checked on reading.
inline constexpr std::string_view kReplaysFormat = "talus-testbed-replays";
inline constexpr int kReplaysVersion = 1;

/// The results as one JSON text, trajectories inside each result (2-space
/// indented, ends with a newline).
std::string ResultsToJson(const ResultsFile& file);

/// Parses results JSON of either form; the file form ("trajectories" at
/// the top) needs `trajectoryText`, its trajectory file's text, and
/// `replayText`, its replay file's, unless the trajectory file predates
/// the replay file (no "replays" count in it). An Error
/// names the place (e.g. "results/3/metrics/0: missing field
/// \"measured\"", "trajectory file: /trajectories/2: ...") when a text is
/// not what it should be.
Result<ResultsFile> ResultsFromJson(std::string_view text, std::string_view trajectoryText = {},
                                    std::string_view replayText = {});

/// The first result of `results` whose (run id, backend) pair an earlier
/// one already has, as the indices of both (earlier first); nullopt when
/// every pair appears once. A results file holds each job once: a
/// duplicate (two merged copies, a backend edited by hand) would be
/// counted twice by every table.
std::optional<std::pair<std::size_t, std::size_t>> FindDuplicatedResult(
    const std::vector<RunResult>& results);

/// One RunResult as bytes (CBOR of its results.json entry, with every
/// number exact: NaN and infinities kept), for an isolated job's answer to
/// the runner (job_processes.h), and back. Every field results.json
/// carries travels, so a result that crossed a process boundary writes the
/// same results.json bytes as one that did not.
std::string RunResultToWire(const RunResult& result);
Result<RunResult> RunResultFromWire(std::string_view bytes);

/// Where the trajectories of the results file at `resultsPath` go: beside
/// it, its name with ".json" replaced by ".trajectories.json".
std::filesystem::path TrajectoryFilePath(const std::filesystem::path& resultsPath);

/// Where the replays of the results file at `resultsPath` go: beside it,
/// its name with ".json" replaced by ".replays.json".
std::filesystem::path ReplayFilePath(const std::filesystem::path& resultsPath);

/// The three files that hold `file` at `path`: results.json without the
/// trajectories, the trajectory file (plot series) and the replay file.
/// For writers of a larger set of files (the report, the sweep).
std::vector<FileText> ResultsFileTexts(const std::filesystem::path& path, const ResultsFile& file);

/// Writes the three files as one set / reads them back (or a one-text
/// results file, or a two-file set written before the replay file, whose
/// replays are in the trajectory file's lines); errors name the path.
Result<std::monostate> WriteResultsFile(const std::filesystem::path& path, const ResultsFile& file);
Result<ResultsFile> ReadResultsFile(const std::filesystem::path& path);

}  // namespace talus::harness
