// talus-sat-check: the SAT validation program. Runs RunSatCheck, writes the
// JSON and Markdown reports (docs/collision-validation.md) and exits
// non-zero when a Talus mode breaks a stated bound.
//
// Exit status: 0 every Talus mode within its bounds; 1 a bound broken (the
// summary line on stderr names the first); 2 bad arguments or a report that
// could not be written.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <system_error>

#include "flag_range.h"
#include "sat_check.h"

namespace {

// Writes `text` to a temporary name beside `path`, then renames it over
// `path`: a failed or interrupted run never leaves a half-written report.
// (A local helper: talus-sat-check does not link the harness, where a
// shared one is being added.)
bool WriteTextAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    file << text;
    file.close();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return false;
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) std::filesystem::remove(temporary, error);
  return !error;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"talus-sat-check: Talus's SAT against libccd, Bullet and the exact Minkowski truth"};
  talus::validation::SatCheckSettings settings;
  std::string jsonPath;
  std::string markdownPath;
  app.add_option("--pairs", settings.pairs,
                 "number of random shape pairs (1 to " + std::to_string(talus::validation::kMaxPairs) + ")")
      ->check(talus::flags::InRange(1, talus::validation::kMaxPairs))
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
  CLI11_PARSE(app, argc, argv);
  const auto seed = talus::validation::ParseSeed(seedText);
  if (!seed) {
    std::cerr << "talus-sat-check: " << seed.GetError().message << "\n";
    return 2;
  }
  settings.seed = seed.Value();

  const auto report = talus::validation::RunSatCheck(settings);
  if (!report) {
    std::cerr << "talus-sat-check: " << report.GetError().message << "\n";
    return 2;
  }
  if (!jsonPath.empty() && !WriteTextAtomically(jsonPath, talus::validation::ReportToJson(report.Value()))) {
    std::cerr << "talus-sat-check: cannot write " << jsonPath << "\n";
    return 2;
  }
  const std::string markdown = talus::validation::ReportToMarkdown(report.Value());
  if (markdownPath.empty()) {
    std::cout << markdown;
  } else if (!WriteTextAtomically(markdownPath, markdown)) {
    std::cerr << "talus-sat-check: cannot write " << markdownPath << "\n";
    return 2;
  }
  std::cerr << "talus-sat-check: " << talus::validation::SummaryLine(report.Value()) << "\n";
  return report.Value().failures.empty() ? 0 : 1;
}
