// The results file of a testbed run (results.json): every RunResult with
// its metrics, settings, timings and plot series, in the runner's order.
// Schema in docs/testbed-runner.md. NaN numbers (nothing measured, no
// integrator answer) are written as null and read back as NaN. Writing is
// deterministic: fixed key order, numbers in shortest round-trip form, so
// equal results give byte-identical files.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "talus/harness/run/runner.h"
#include "talus/result.h"

namespace talus::harness {

/// The file's "format" value, checked on reading.
inline constexpr std::string_view kResultsFormat = "talus-testbed-results";
/// The file's "version" value, checked on reading.
inline constexpr int kResultsVersion = 1;

/// A whole run of the testbed.
struct ResultsFile {
  std::vector<std::string> backends;  ///< as asked, in order
  bool deterministic = false;         ///< wall times were zeroed
  std::vector<RunResult> results;     ///< runs x backends, run-major
};

/// The results as JSON text (2-space indented, ends with a newline).
std::string ResultsToJson(const ResultsFile& file);

/// Parses results JSON; an Error names the place (e.g. "results/3/metrics/0:
/// missing field \"measured\"") when the text is not a results file.
Result<ResultsFile> ResultsFromJson(std::string_view text);

/// One RunResult as bytes (CBOR of its results.json entry, with every
/// number exact: NaN and infinities kept), for an isolated job's answer to
/// the runner (job_processes.h), and back. Every field results.json
/// carries travels, so a result that crossed a process boundary writes the
/// same results.json bytes as one that did not.
std::string RunResultToWire(const RunResult& result);
Result<RunResult> RunResultFromWire(std::string_view bytes);

/// Writes / reads the file; errors name the path.
Result<std::monostate> WriteResultsFile(const std::filesystem::path& path, const ResultsFile& file);
Result<ResultsFile> ReadResultsFile(const std::filesystem::path& path);

}  // namespace talus::harness
