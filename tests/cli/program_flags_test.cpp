// Every numeric flag of every program refuses a value outside its range
// with the flag, the value and the range (issue 26), NaN included, and
// exits 2 before doing anything; `talus frobnicate` names the word it did
// not know.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/command_outcome.h"

namespace program_flags_test {

using talus::testing_support::CommandOutcome;
using talus::testing_support::RunCommand;

struct Refusal {
  std::string arguments;  ///< after the program's path
  std::string message;    ///< what the output must hold
};

// `code`: the exit status every refusal must give (2: bad input).
void ExpectRefused(const std::string& program, const std::vector<Refusal>& refusals, int code = 2) {
  for (const Refusal& refusal : refusals) {
    const CommandOutcome outcome = RunCommand(program + " " + refusal.arguments);
    EXPECT_EQ(outcome.code, code) << refusal.arguments << ": " << outcome.output;
    EXPECT_NE(outcome.output.find(refusal.message), std::string::npos) << refusal.arguments << ":\n"
                                                                       << outcome.output;
    // No bound printed as hundreds of digits (std::to_string of DBL_MAX).
    EXPECT_LT(outcome.output.size(), 400u) << refusal.arguments << ": " << outcome.output;
  }
}

const std::string kCube = std::string(TALUS_TEST_DATA_DIR) + "/cli/cube.xyz";

TEST(ProgramFlags, TalusNamesAnUnknownSubcommand) {
  const CommandOutcome outcome = RunCommand(std::string(TALUS_CLI_BINARY) + " frobnicate " + kCube);
  EXPECT_EQ(outcome.code, 2);
  EXPECT_NE(outcome.output.find("talus: unknown subcommand \"frobnicate\" (known: hull)"), std::string::npos)
      << outcome.output;
}

TEST(ProgramFlags, TalusHullRefusesDensitiesAndCapsOutOfRange) {
  const std::string positive = "is outside the range above 0 up to 1.7976931348623157e+308";
  ExpectRefused(
      std::string(TALUS_CLI_BINARY),
      {{"hull " + kCube + " --density -1", "--density: -1 " + positive},
       {"hull " + kCube + " --density 0", "--density: 0 " + positive},
       {"hull " + kCube + " --density nan", "--density: nan " + positive},
       {"hull " + kCube + " --density 1e999", "--density: 1e999 " + positive},
       {"hull " + kCube + " --max-vertices -3", "--max-vertices: -3 is outside the range 0 to 2147483647"},
       {"hull " + kCube + " --max-vertices 4x", "--max-vertices: \"4x\" is not a number in the range"}});
}

#ifdef TALUS_SCENES_BINARY
TEST(ProgramFlags, ScenesRefusesParametersStepsThreadsAndSeedsOutOfRange) {
  const std::string base = " --scene pyramid --engines talus ";
  ExpectRefused(std::string(TALUS_SCENES_BINARY),
                {{base + "--param -3", "--param: -3 is outside the range 1 to 100"},
                 {base + "--param 101", "--param: 101 is outside the range 1 to 100"},
                 {base + "--steps 0", "--steps: 0 is outside the range 1 to 1000000"},
                 {base + "--threads 1,257", "--threads: 257 is outside the range 1 to 256"},
                 {base + "--perturb 1e-9 --perturb-seed -1",
                  "--perturb-seed: -1 is outside the range 0 to 18446744073709551615"}});
}
#endif

#ifdef TALUS_TESTBED_BINARY
TEST(ProgramFlags, TestbedRefusesTimeStepsIterationsJobsThreadsAndBudgetsOutOfRange) {
  const std::string timeStep = "is outside the range above 0 up to 1";
  ExpectRefused(std::string(TALUS_TESTBED_BINARY),
                {{"run --time-step 0", "--time-step: 0 " + timeStep},
                 {"run --time-step 0.01,nan", "--time-step: nan " + timeStep},
                 {"run --time-step 2", "--time-step: 2 " + timeStep},
                 {"run --iterations -1", "--iterations: -1 is outside the range 0 to 100000"},
                 {"run --iterations 100001", "--iterations: 100001 is outside the range 0 to 100000"},
                 {"run --jobs 5000", "--jobs: 5000 is outside the range 0 to 1024"},
                 {"run --threads 0", "--threads: 0 is outside the range 1 to 256"},
                 {"run --budget -1", "--budget: -1 is not 0 (none) or 0 to 1000000 s"},
                 {"run --budget nan", "--budget: nan is not 0 (none) or 0 to 1000000 s"},
                 {"run --memory-limit 3", "--memory-limit: 3 is not 0 (none) or 16 to 1048576 MiB"},
                 {"check --jobs -1", "--jobs: -1 is outside the range 0 to 1024"},
                 {"sweep --time-step -0.01", "--time-step: -0.01 " + timeStep},
                 {"sweep --iterations 5,-5", "--iterations: -5 is outside the range 0 to 100000"},
                 {"sweep --jobs 1025", "--jobs: 1025 is outside the range 0 to 1024"}});
}
#endif

#ifdef TALUS_SAT_CHECK_BINARY
TEST(ProgramFlags, SatCheckRefusesPairsAndRepeatsOutOfRange) {
  ExpectRefused(std::string(TALUS_SAT_CHECK_BINARY),
                {{"--pairs 0", "--pairs: 0 is outside the range 1 to 1000000"},
                 {"--pairs 1000001", "--pairs: 1000001 is outside the range 1 to 1000000"},
                 {"--repeats -1", "--repeats: -1 is outside the range 0 to 1000"}},
                /*code=*/2);  // bad arguments, as every other bad input of talus-sat-check
}
#endif

}  // namespace program_flags_test
