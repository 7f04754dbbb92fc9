// The talus-testbed command line refuses hostile arguments with a message
// that names the argument and the limit (issue 14), and `run` reports a
// run whose step failed while the others finish.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

#ifdef TALUS_TESTBED_BINARY
namespace fs = std::filesystem;

struct Outcome {
  int code = -1;
  std::string output;  // stdout and stderr together
};

Outcome Execute(const std::string& arguments) {
  // One log per test and process: ctest runs these tests in parallel.
  const fs::path log =
      fs::temp_directory_path() / (std::string("talus_command_refusals_") +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                                   std::to_string(::getpid()) + ".log");
  const int status = std::system(
      (std::string(TALUS_TESTBED_BINARY) + " " + arguments + " >" + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(TestbedCommand, AnUnknownSubcommandIsNamedWithTheKnownOnes) {
  const Outcome outcome = Execute("frobnicate");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, "unknown subcommand \"frobnicate\" (known: run, report, check"))
      << outcome.output;
}

TEST(TestbedCommand, AHugeJobCountIsRefusedWithItsRange) {
  const Outcome outcome = Execute("run --jobs 1000000 -q");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, "1024")) << outcome.output;
}

TEST(TestbedCommand, ARunWhoseStepFailsIsReportedAndTheOthersFinish) {
  const fs::path out = fs::temp_directory_path() / "talus_command_refusals_run";
  fs::remove_all(out);
  const std::string scenario = std::string(TALUS_TEST_DATA_DIR) + "/scenarios_hostile/gravity_to_bound.json";
  const Outcome outcome =
      Execute("run " + scenario + " -q --deterministic -b talus,bullet -j 1 -o " + out.string());
  EXPECT_EQ(outcome.code, 1);  // a run failed (it used to exit 0 with "error": "")
  EXPECT_TRUE(Has(outcome.output, "gravity_to_bound with talus failed: step 142: talus: World::Step refused"))
      << outcome.output;
  EXPECT_FALSE(Has(outcome.output, "with bullet failed")) << outcome.output;
  std::ifstream results(out / "results.json");
  std::ostringstream text;
  text << results.rdbuf();
  EXPECT_TRUE(Has(text.str(), "\"error\": \"step 142: talus: World::Step refused"))
      << text.str().substr(0, 2000);
  // Written whole through a temporary sibling, which is gone.
  for (const auto& entry : fs::directory_iterator(out)) EXPECT_EQ(entry.path().filename(), "results.json");
}

TEST(TestbedCommand, AnUnknownReplaySelectorIsRefused) {
  const std::string scenario = std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json";
  const Outcome outcome = Execute("run " + scenario + " -q -b talus --replay box_rst -o " +
                                  (fs::temp_directory_path() / "talus_command_refusals_replay").string());
  EXPECT_EQ(outcome.code, 2);
  EXPECT_TRUE(Has(outcome.output, "replay: \"box_rst\" names no run id or scenario name")) << outcome.output;
}
#endif

}  // namespace
