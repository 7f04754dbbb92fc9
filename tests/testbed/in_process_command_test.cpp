// `talus-testbed run --in-process` (and `check --in-process`): the jobs on
// threads of the testbed's own process, so a debugger's breakpoint in the
// runner or an engine is hit. The physics must not depend on where a job
// runs, so the results file is the same bytes as the one the child
// processes write; a memory limit needs a process of its own, so the
// command refuses the two flags together.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/scratch_files.h"
#include "testbed/testbed_command.h"

namespace in_process_command_test {

#ifdef TALUS_TESTBED_BINARY
namespace fs = std::filesystem;

using Outcome = talus::testing_support::CommandOutcome;
using talus::testing_support::Contains;
using talus::testing_support::FreshScratchDir;
using talus::testing_support::ReadWholeFile;
using talus::testing_support::RunTestbed;

// Two scenarios through Talus and a peer, at two jobs: once in child
// processes (the default), once in process; every file of the set matches.
TEST(TestbedCommand, InProcessJobsWriteTheSameResultsAsChildProcesses) {
  const std::string scenarios = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_column_2.json " +
                                std::string(TALUS_SCENARIO_DIR) + "/sliding/box_slide.json";
  const fs::path base = FreshScratchDir("in_process_" + std::to_string(::getpid()));
  const std::string common = "run " + scenarios + " -q --deterministic -b talus,bullet -j 2 -o ";
  const Outcome children = RunTestbed(common + (base / "children").string());
  const Outcome inProcess = RunTestbed(common + (base / "in_process").string() + " --in-process");
  ASSERT_EQ(children.code, 0) << children.output;
  ASSERT_EQ(inProcess.code, 0) << inProcess.output;
  for (const char* name : {"results.json", "results.trajectories.json", "results.replays.json"}) {
    const std::string expected = ReadWholeFile(base / "children" / name);
    EXPECT_FALSE(expected.empty()) << name;
    EXPECT_EQ(ReadWholeFile(base / "in_process" / name), expected) << name;
  }
  fs::remove_all(base);
}

TEST(TestbedCommand, InProcessRefusesAMemoryLimitNamingBothFlags) {
  const Outcome outcome = RunTestbed("run -q --in-process --memory-limit 100");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Contains(outcome.output, "--in-process")) << outcome.output;
  EXPECT_TRUE(Contains(outcome.output, "--memory-limit")) << outcome.output;
}

TEST(TestbedCommand, CheckRunsInProcessToo) {
  const Outcome outcome = RunTestbed("check " + std::string(TALUS_SCENARIO_DIR) +
                                     "/stacking/box_column_2.json -q -b talus --in-process");
  EXPECT_EQ(outcome.code, 0) << outcome.output;
}
#endif

}  // namespace in_process_command_test
