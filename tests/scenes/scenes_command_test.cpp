// talus-scenes refuses a parameter of 0 (which meant "the default" inside
// the program and was silently accepted), an engine list naming no engine
// (which ran nothing and exited 0) and a thread list naming a count twice;
// a thread list runs each Talus engine once per count; lists of iteration
// and substep counts run every engine once per setting, and a setting out
// of range or one an engine has no knob for is refused before anything runs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "support/command_outcome.h"

namespace scenes_command_test {

#ifdef TALUS_SCENES_BINARY
using Outcome = talus::testing_support::CommandOutcome;

Outcome Execute(const std::string& arguments) {
  return talus::testing_support::RunCommand(std::string(TALUS_SCENES_BINARY) + " " + arguments);
}

TEST(ScenesCommand, AParameterOfZeroIsRefused) {
  for (const char* value : {"0", "-3"}) {
    const Outcome outcome = Execute(std::string("--scene pyramid --param ") + value + " --steps 1");
    EXPECT_NE(outcome.code, 0) << value;
    EXPECT_NE(outcome.output.find("--param"), std::string::npos) << outcome.output;
  }
}

TEST(ScenesCommand, AnEngineListNamingNoEngineIsRefused) {
  const Outcome outcome = Execute("--scene pyramid --param 1 --steps 1 --engines ,");
  EXPECT_EQ(outcome.code, 2);
  EXPECT_NE(outcome.output.find("--engines \",\" names no engine"), std::string::npos) << outcome.output;
}
TEST(ScenesCommand, AThreadListRunsEachTalusEngineOncePerCountAndEachPeerOnce) {
  const Outcome outcome =
      Execute("--scene pyramid --param 1 --steps 2 --engines talus,bullet --threads 1,2 --format csv");
  ASSERT_EQ(outcome.code, 0) << outcome.output;
  // Talus at 1 then 2 threads, right after each other, then Bullet once.
  const std::size_t one = outcome.output.find("\ntalus,pyramid,1,1,1,2,");
  const std::size_t two = outcome.output.find("\ntalus,pyramid,1,1,2,2,");
  const std::size_t peer = outcome.output.find("\nbullet,pyramid,1,1,1,2,");
  ASSERT_NE(one, std::string::npos) << outcome.output;
  ASSERT_NE(two, std::string::npos) << outcome.output;
  ASSERT_NE(peer, std::string::npos) << outcome.output;
  EXPECT_LT(one, two);
  EXPECT_LT(two, peer);
  EXPECT_EQ(outcome.output.find("\nbullet", peer + 1), std::string::npos) << outcome.output;
  // Talus's lines end with its stage medians; Bullet times no stages.
  EXPECT_NE(outcome.output.find("UpdateBroadPhase=", one), std::string::npos) << outcome.output;
}

TEST(ScenesCommand, AThreadCountNamedTwiceOrOutOfRangeIsRefused) {
  const Outcome twice = Execute("--scene pyramid --param 1 --steps 1 --engines talus --threads 2,1,2");
  EXPECT_EQ(twice.code, 2);
  EXPECT_NE(twice.output.find("--threads names 2 twice"), std::string::npos) << twice.output;
  const Outcome zero = Execute("--scene pyramid --param 1 --steps 1 --engines talus --threads 1,0");
  EXPECT_NE(zero.code, 0);
  EXPECT_NE(zero.output.find("--threads"), std::string::npos) << zero.output;
}
TEST(ScenesCommand, IterationAndSubstepListsRunEveryEngineOncePerSetting) {
  const Outcome outcome = Execute(
      "--scene pyramid --param 1 --steps 2 --engines talus,bullet --iterations 0,4 --substeps 1,2 --format "
      "csv");
  ASSERT_EQ(outcome.code, 0) << outcome.output;
  // engine,scene,parameter,bodies,threads,steps,iterations,substeps: each
  // engine's four settings in list order, Talus's before Bullet's.
  std::size_t last = 0;
  for (const char* engine : {"talus", "bullet"}) {
    for (const char* setting : {"0,1", "0,2", "4,1", "4,2"}) {
      const std::string line = std::string("\n") + engine + ",pyramid,1,1,1,2," + setting + ",";
      const std::size_t at = outcome.output.find(line);
      ASSERT_NE(at, std::string::npos) << line << " in " << outcome.output;
      EXPECT_GT(at, last) << line;
      EXPECT_EQ(outcome.output.find(line, at + 1), std::string::npos) << line << " twice";
      last = at;
    }
  }
}

TEST(ScenesCommand, SettingsOutOfRangeOrWithoutAKnobAreRefusedBeforeAnyRun) {
  const std::string base = "--scene pyramid --param 1 --steps 1 ";
  for (const auto& [arguments, message] :
       {std::pair<const char*, const char*>{
            "--engines talus --iterations 4,1001",
            "talus-scenes: --iterations: iterations 1001: must be in [0, 1000] "
            "(0: the engine's default)"},
        {"--engines talus --iterations -1",
         "talus-scenes: --iterations: iterations -1: must be in [0, 1000]"},
        {"--engines talus --substeps 1,0", "talus-scenes: --substeps: substeps 0: must be in [1, 100]"},
        {"--engines talus --substeps 101", "talus-scenes: --substeps: substeps 101: must be in [1, 100]"},
        {"--engines talus,ode-step --iterations 0,8",
         "talus-scenes: --iterations: iterations 8: ode-step has no iteration count (dWorldStep solves each "
         "island directly, a Dantzig LCP)"},
        {"--engines talus --iterations 4,4", "talus-scenes: --iterations names 4 twice"},
        {"--engines talus --substeps 2,2", "talus-scenes: --substeps names 2 twice"}}) {
    const Outcome outcome = Execute(base + arguments);
    EXPECT_EQ(outcome.code, 2) << arguments << ": " << outcome.output;
    EXPECT_NE(outcome.output.find(message), std::string::npos) << arguments << ": " << outcome.output;
    // Nothing ran: not even the CSV header was written.
    EXPECT_EQ(outcome.output.find("engine,scene"), std::string::npos) << arguments << ": " << outcome.output;
  }
  // ode-step at its only setting (no --iterations, or 0) runs.
  const Outcome plain = Execute(base + "--engines ode-step --iterations 0 --substeps 2");
  EXPECT_EQ(plain.code, 0) << plain.output;
}
#endif

}  // namespace scenes_command_test
