// talus-sat-check: the SAT validation program. Runs RunSatCheck and writes
// the JSON and Markdown reports (docs/collision-validation.md).
#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>

#include "sat_check.h"

int main(int argc, char** argv) {
  CLI::App app{"talus-sat-check: Talus's SAT against libccd, Bullet and the exact Minkowski truth"};
  talus::validation::SatCheckSettings settings;
  std::string jsonPath;
  std::string markdownPath;
  app.add_option("--pairs", settings.pairs, "number of random shape pairs (>= 1)")->capture_default_str();
  app.add_option("--seed", settings.seed, "generator seed")->capture_default_str();
  app.add_option("--repeats", settings.timingRepeats, "timed repeats per query (0: no timing)")
      ->capture_default_str();
  app.add_option("--json", jsonPath, "write the full report as JSON to this file");
  app.add_option("--markdown", markdownPath, "write the Markdown section to this file (default: stdout)");
  CLI11_PARSE(app, argc, argv);

  const auto report = talus::validation::RunSatCheck(settings);
  if (!report) {
    std::cerr << "talus-sat-check: " << report.GetError().message << "\n";
    return 2;
  }
  if (!jsonPath.empty()) {
    std::ofstream file(jsonPath);
    file << talus::validation::ReportToJson(report.Value());
    if (!file) {
      std::cerr << "talus-sat-check: cannot write " << jsonPath << "\n";
      return 1;
    }
  }
  const std::string markdown = talus::validation::ReportToMarkdown(report.Value());
  if (markdownPath.empty()) {
    std::cout << markdown;
  } else {
    std::ofstream file(markdownPath);
    file << markdown;
    if (!file) {
      std::cerr << "talus-sat-check: cannot write " << markdownPath << "\n";
      return 1;
    }
  }
  return 0;
}
