// The subcommands of `talus-testbed` (docs/testbed-runner.md): each takes
// its parsed options and returns the process exit code, printing results on
// stdout and errors and progress on stderr.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace talus::testbed {

/// Exit codes: 0 success; 1 a check found regressions or a run failed;
/// 2 bad input (arguments, scenario files, results files) or an output
/// (a file or stdout) that could not be written.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;
inline constexpr int kExitBadInput = 2;

/// The backends `run` uses when none are named: Talus's three variants and
/// every peer.
std::vector<std::string> DefaultBackends();

struct RunOptions {
  std::vector<std::string> scenarios;  ///< files or folders; empty = the default folder
  std::vector<std::string> backends;   ///< empty = DefaultBackends()
  std::vector<double> timeSteps;       ///< seconds; each run again per value (empty = the file's)
  std::vector<int> iterations;         ///< each run again per value, 0 = engine default (empty = the file's)
  std::string out = "reports/latest";  ///< folder for results.json
  int jobs = 0;                        ///< 0 = every core
  int threads = 1;                     ///< WorldSettings::threads of the Talus backends
  bool deterministic = false;          ///< zero wall times
  bool quiet = false;                  ///< no progress lines
  std::vector<std::string> replay;     ///< runs to record for the 3D replay: ids, scenario names or "all"
  /// Write the trajectory file exact rather than in the display form
  /// (harness display_trajectory.h); the metrics are the same either way.
  bool fullTrajectories = false;
  /// Wall-clock seconds per job before it is stopped (0 = none); the
  /// default leaves the longest default-suite job (docs/testbed-runner.md,
  /// "Isolated jobs") a hundredfold margin and ends a hang within the hour.
  double budget = 1800.0;
  /// Address space each job's process may add, MiB (0 = none); the default
  /// is far above any suite job's and far below what the CI machine has.
  std::size_t memoryLimitMiB = 8192;
  /// Run the jobs on threads of this process (JobIsolation::InProcess)
  /// instead of a child process each, so a debugger's breakpoint in
  /// RunOne or an engine is hit. Nothing then protects the other jobs from
  /// one that crashes; the budget stops a job between steps but cannot
  /// kill one stuck inside a step; memoryLimitMiB is not applied (a limit
  /// needs a process of its own; the command line refuses both flags
  /// together).
  bool inProcess = false;
};
int RunCommand(const RunOptions& options);

struct ReportOptions {
  std::string results;   ///< results.json of a run
  std::string out;       ///< report folder; empty = the results file's folder
  std::string chartJs;   ///< charting library; empty = the npm copy under harness/report
  std::string threeJs;   ///< three.js (3D views); empty = the npm copy under harness/report
  std::string satCheck;  ///< talus-sat-check --json output to add as a section; empty = none
  std::string sweep;     ///< a sweep's results.json to add as run time against error; empty = none
  std::string stress;    ///< talus-testbed stress's stress.json to add as the envelope; empty = none
  std::string scenes;    ///< talus-scenes --format jsonl output to add as large scenes; empty = none
};
int ReportCommand(const ReportOptions& options);

struct CheckOptions {
  std::vector<std::string> scenarios;  ///< as for run, when no results file is given
  std::string results;                 ///< check this results.json instead of running
  std::vector<std::string> backends;   ///< whose metrics are checked; empty = every Talus variant
  int jobs = 0;                        ///< 0 = every core
  bool quiet = false;
  bool inProcess = false;  ///< as RunOptions::inProcess, for the run check makes
};
int CheckCommand(const CheckOptions& options);

/// The exit code once stdout has been flushed: `code`, or kExitBadInput
/// (after "talus-testbed: stdout: cannot write (REASON)" on stderr) when
/// stdout did not take everything printed (a full disk, a directory).
int FinishStdout(int code);

}  // namespace talus::testbed
