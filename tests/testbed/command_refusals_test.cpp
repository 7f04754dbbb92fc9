// The talus-testbed command line refuses hostile arguments with a message
// that names the argument and the limit (issue 14), and `run` reports a
// run whose step failed while the others finish.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "testbed/testbed_command.h"

namespace command_refusals_test {

#ifdef TALUS_TESTBED_BINARY
namespace fs = std::filesystem;

using Outcome = talus::testing_support::CommandOutcome;
using talus::testing_support::Contains;
using talus::testing_support::RunTestbed;

TEST(TestbedCommand, AnUnknownSubcommandIsNamedWithTheKnownOnes) {
  const Outcome outcome = RunTestbed("frobnicate");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Contains(outcome.output, "unknown subcommand \"frobnicate\" (known: run, report, check"))
      << outcome.output;
}

TEST(TestbedCommand, AHugeJobCountIsRefusedWithItsRange) {
  const Outcome outcome = RunTestbed("run --jobs 1000000 -q");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Contains(outcome.output, "1024")) << outcome.output;
}

TEST(TestbedCommand, OutOfRangeLimitsAreRefusedNamingTheFlagTheValueAndTheRange) {
  const struct {
    const char* arguments;
    const char* expected;
  } cases[] = {
      {"--budget -1", "--budget: -1 is not 0 (none) or 0 to 1000000 s"},
      {"--budget nan", "--budget: nan is not 0 (none) or 0 to 1000000 s"},
      {"--budget 2e6", "--budget: 2e6 is not 0 (none) or 0 to 1000000 s"},
      {"--memory-limit 8", "--memory-limit: 8 is not 0 (none) or 16 to 1048576 MiB"},
      {"--memory-limit 1e9", "--memory-limit: 1e9 is not 0 (none) or 16 to 1048576 MiB"},
  };
  for (const auto& c : cases) {
    const Outcome outcome = RunTestbed(std::string("run -q ") + c.arguments);
    EXPECT_EQ(outcome.code, 2) << c.arguments;
    EXPECT_TRUE(Contains(outcome.output, c.expected)) << c.arguments << ": " << outcome.output;
  }
}

TEST(TestbedCommand, ARunWhoseStepFailsIsReportedAndTheOthersFinish) {
  const fs::path out = fs::temp_directory_path() / "talus_command_refusals_run";
  fs::remove_all(out);
  const std::string scenario = std::string(TALUS_TEST_DATA_DIR) + "/scenarios_hostile/gravity_to_bound.json";
  const Outcome outcome =
      RunTestbed("run " + scenario + " -q --deterministic -b talus,bullet -j 1 -o " + out.string());
  EXPECT_EQ(outcome.code, 1);  // a run failed (it used to exit 0 with "error": "")
  // Step 143: talus falls exactly for constant gravity (step_failure_test.cpp).
  EXPECT_TRUE(
      Contains(outcome.output, "gravity_to_bound with talus failed: step 143: talus: World::Step refused"))
      << outcome.output;
  EXPECT_FALSE(Contains(outcome.output, "with bullet failed")) << outcome.output;
  std::ifstream results(out / "results.json");
  std::ostringstream text;
  text << results.rdbuf();
  EXPECT_TRUE(Contains(text.str(), "\"error\": \"step 143: talus: World::Step refused"))
      << text.str().substr(0, 2000);
  // Written whole, with its trajectory and replay files, through temporary siblings, which are gone.
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "results.json" || name == "results.trajectories.json" ||
                name == "results.replays.json")
        << name;
  }
}

TEST(TestbedCommand, AnUnknownReplaySelectorIsRefused) {
  const std::string scenario = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json";
  const Outcome outcome = RunTestbed("run " + scenario + " -q -b talus --replay box_rst -o " +
                                     (fs::temp_directory_path() / "talus_command_refusals_replay").string());
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Contains(outcome.output, "replay: \"box_rst\" names no run id or scenario name"))
      << outcome.output;
}
#endif

}  // namespace command_refusals_test
