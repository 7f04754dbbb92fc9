// Every program whose output cannot be written says which output and why,
// and exits non-zero (issue 26, "Outputs all or nothing"): stdout on a full
// device (/dev/full), an output path that is a folder or a device, and a
// report on a full disk, which must leave the report folder's set of files
// as it was. The full disk is a file size limit (ulimit -f, with SIGXFSZ
// ignored so that a write past it fails with EFBIG instead of killing the
// program).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/command_outcome.h"
#include "support/scratch_files.h"

namespace program_outputs_test {

namespace fs = std::filesystem;
using talus::testing_support::CommandOutcome;
using talus::testing_support::RunCommand;

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Appended piece by piece: GCC 12 mis-warns -Wrestrict on "'" + string.
std::string Quote(const fs::path& path) {
  std::string quoted = "'";
  quoted.append(path.string()).append("'");
  return quoted;
}

fs::path Fresh(const std::string& name) {
  return talus::testing_support::FreshScratchDir("program_outputs_" + name);
}

std::string Read(const fs::path& path) { return talus::testing_support::ReadWholeFile(path); }

// RunCommand sends stdout to its log; this sends it to `target` and keeps
// stderr in the log.
CommandOutcome WithStdout(const std::string& command, const std::string& target) {
  return RunCommand("{ " + command + " >" + target + "; }");
}

const std::string kCube = std::string(TALUS_TEST_DATA_DIR) + "/cli/cube.xyz";

TEST(ProgramOutputs, TalusHullOnAFullStdoutSaysSoAndFails) {
  const CommandOutcome outcome = WithStdout(std::string(TALUS_CLI_BINARY) + " hull " + kCube, "/dev/full");
  EXPECT_EQ(outcome.code, 1);
  EXPECT_TRUE(Has(outcome.output, "talus hull: stdout: cannot write (No space left on device)"))
      << outcome.output;
}

TEST(ProgramOutputs, TalusHullIntoAFolderNamesItAndLeavesNothing) {
  const fs::path dir = Fresh("hull_folder");
  fs::create_directories(dir / "out.obj");
  const CommandOutcome outcome =
      RunCommand(std::string(TALUS_CLI_BINARY) + " hull " + kCube + " -o " + Quote(dir / "out.obj"));
  EXPECT_EQ(outcome.code, 1);
  EXPECT_TRUE(Has(outcome.output, (dir / "out.obj").string() + ": cannot replace file")) << outcome.output;
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"out.obj"});
}

#ifdef TALUS_SCENES_BINARY
TEST(ProgramOutputs, ScenesOnAFullStdoutSaysSoAndStops) {
  const CommandOutcome outcome = WithStdout(
      std::string(TALUS_SCENES_BINARY) + " --scene pyramid --param 1 --steps 1 --engines talus", "/dev/full");
  EXPECT_EQ(outcome.code, 1);
  EXPECT_TRUE(Has(outcome.output, "talus-scenes: stdout: cannot write (No space left on device)"))
      << outcome.output;
}
#endif

#ifdef TALUS_TESTBED_BINARY
const std::string kBoxRest = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json";

std::string Testbed(const std::string& arguments) {
  return std::string(TALUS_TESTBED_BINARY) + " " + arguments;
}

TEST(ProgramOutputs, TestbedRunOnAFullStdoutSaysSoAndFails) {
  const fs::path dir = Fresh("run_stdout");
  const CommandOutcome outcome =
      WithStdout(Testbed("run " + kBoxRest + " -b talus -q --deterministic -o " + Quote(dir)), "/dev/full");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, "talus-testbed: stdout: cannot write (No space left on device)"))
      << outcome.output;
}

TEST(ProgramOutputs, TestbedRunIntoADeviceNamesIt) {
  const CommandOutcome outcome = RunCommand(Testbed("run " + kBoxRest + " -b talus -q -o /dev/full"));
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, "talus-testbed: /dev/full: cannot make the output folder"))
      << outcome.output;
}

// A run with a replay: the set holds results.json, its trajectory file
// (series and replay), the report's pages and its data file.
fs::path RunWithReplay(const std::string& name) {
  const fs::path dir = Fresh(name);
  const CommandOutcome run = RunCommand(
      Testbed("run " + kBoxRest + " -b talus -q --deterministic --replay all -o " + Quote(dir / "run")));
  EXPECT_EQ(run.code, 0) << run.output;
  return dir;
}

// The files of a folder with their contents.
std::vector<std::pair<std::string, std::string>> Contents(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    files.emplace_back(entry.path().filename().string(),
                       fs::is_regular_file(entry.path()) ? Read(entry.path()) : std::string("(folder)"));
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ProgramOutputs, TestbedReportOnAFullDiskLeavesTheOldSetWhole) {
  const fs::path dir = RunWithReplay("report_full_disk");
  const fs::path out = dir / "report";
  fs::create_directories(out);
  std::ofstream(out / "summary.md") << "old summary\n";
  std::ofstream(out / "report.html") << "old page\n";
  const auto before = Contents(out);
  // 256 kB per file: summary.md and the CSV fit, report.html (three.js and
  // Chart.js inlined, over 1 MB) does not.
  const CommandOutcome outcome =
      RunCommand("trap '' XFSZ; ulimit -f 256; " +
                 Testbed("report " + Quote(dir / "run" / "results.json") + " -o " + Quote(out)));
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, (out / "report.html").string() + ": cannot write (File too large)"))
      << outcome.output;
  EXPECT_EQ(Contents(out), before);
}

TEST(ProgramOutputs, TestbedReportWhoseLastRenameFailsPutsTheSetBack) {
  const fs::path dir = RunWithReplay("report_rename_fails");
  const fs::path out = dir / "report";
  fs::create_directories(out / "report.html");  // a folder, not empty: its rename fails
  std::ofstream(out / "report.html" / "inside") << "kept\n";
  std::ofstream(out / "summary.md") << "old summary\n";
  const auto before = Contents(out);
  const CommandOutcome outcome =
      RunCommand(Testbed("report " + Quote(dir / "run" / "results.json") + " -o " + Quote(out)));
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, (out / "report.html").string() + ": cannot write (")) << outcome.output;
  EXPECT_EQ(Contents(out), before);
  EXPECT_EQ(Read(out / "report.html" / "inside"), "kept\n");
}

TEST(ProgramOutputs, TestbedReportWritesTheWholeSet) {
  const fs::path dir = RunWithReplay("report_whole_set");
  const CommandOutcome outcome =
      RunCommand(Testbed("report " + Quote(dir / "run" / "results.json") + " -o " + Quote(dir / "report")));
  ASSERT_EQ(outcome.code, 0) << outcome.output;
  std::vector<std::string> names;
  for (const auto& [name, text] : Contents(dir / "report")) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"report-data.js", "report-replay.js", "report.html",
                                             "results.csv", "results.json", "results.replays.json",
                                             "results.trajectories.json", "summary.md"}));
  EXPECT_EQ(Read(dir / "report" / "results.json"), Read(dir / "run" / "results.json"));
  EXPECT_EQ(Read(dir / "report" / "results.trajectories.json"),
            Read(dir / "run" / "results.trajectories.json"));
  EXPECT_EQ(Read(dir / "report" / "results.replays.json"), Read(dir / "run" / "results.replays.json"));
}
#endif

}  // namespace program_outputs_test
