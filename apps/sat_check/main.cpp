// talus-sat-check: the SAT validation program. Runs RunSatCheck, writes the
// JSON and Markdown reports (docs/collision-validation.md) and exits
// non-zero when a Talus mode breaks a stated bound or the truth is broken.
//
// Exit status (sat_check.h): 0 every Talus mode within its bounds; 1 a
// bound broken or a Talus error (the summary line on stderr names the
// first); 2 bad arguments or an output that could not be written; 3 the
// truth disagrees with its own checks (qhull against BuildHull, the box
// closed form), so Talus cannot be judged.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <vector>

#include "flag_range.h"
#include "sat_check.h"
#include "talus/harness/support/atomic_file.h"

int main(int argc, char** argv) {
  namespace validation = talus::validation;
  CLI::App app{"talus-sat-check: Talus's SAT against libccd, Bullet and the exact Minkowski truth"};
  validation::SatCheckSettings settings;
  std::string jsonPath;
  std::string markdownPath;
  app.add_option("--pairs", settings.pairs,
                 "number of random shape pairs (1 to " + std::to_string(validation::kMaxPairs) + ")")
      ->check(talus::flags::InRange(1, validation::kMaxPairs))
      ->capture_default_str();
  // Read as text and checked by ParseSeed: read as a number, "-1" and
  // overflowing values went through without a word (issue 14).
  std::string seedText = std::to_string(settings.seed);
  app.add_option("--seed", seedText, "generator seed, 0 to 2^64 - 1")->capture_default_str();
  // A query's time is its repeats' mean, so more repeats smooth the timer's
  // resolution; past 1000 a run only takes longer.
  app.add_option("--repeats", settings.timingRepeats, "timed repeats per query (0: no timing)")
      ->check(talus::flags::InRange(0, 1000))
      ->capture_default_str();
  app.add_option("--json", jsonPath, "write the full report as JSON to this file");
  app.add_option("--markdown", markdownPath, "write the Markdown section to this file (default: stdout)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : validation::kExitUsage;
  }
  const auto seed = validation::ParseSeed(seedText);
  if (!seed) {
    std::cerr << "talus-sat-check: " << seed.GetError().message << "\n";
    return validation::kExitUsage;
  }
  settings.seed = seed.Value();

  const auto report = validation::RunSatCheck(settings);
  if (!report) {
    std::cerr << "talus-sat-check: " << report.GetError().message << "\n";
    return validation::kExitUsage;
  }
  // Outputs all or nothing (issue 26): stdout first, since it cannot be
  // taken back, then the files as one set (WriteFilesAtomically: a full
  // disk, a folder or a full device named as a file leaves none of them).
  const std::string json = jsonPath.empty() ? std::string() : validation::ReportToJson(report.Value());
  const std::string markdown = validation::ReportToMarkdown(report.Value());
  if (markdownPath.empty()) {
    errno = 0;
    std::cout << markdown << std::flush;
    if (!std::cout) {
      std::cerr << "talus-sat-check: standard output: cannot write ("
                << (errno != 0 ? std::strerror(errno) : "write failed") << ")\n";
      return validation::kExitUsage;
    }
  }
  std::vector<talus::harness::FileText> files;
  if (!jsonPath.empty()) files.push_back({jsonPath, json});
  if (!markdownPath.empty()) files.push_back({markdownPath, markdown});
  const auto written = talus::harness::WriteFilesAtomically(files);
  if (!written) {
    std::cerr << "talus-sat-check: " << written.GetError().message << "; no report written\n";
    return validation::kExitUsage;
  }
  std::cerr << "talus-sat-check: " << validation::SummaryLine(report.Value()) << "\n";
  return validation::ExitStatus(report.Value());
}
