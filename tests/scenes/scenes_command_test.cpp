// talus-scenes refuses a parameter of 0 (which meant "the default" inside
// the program and was silently accepted), an engine list naming no engine
// (which ran nothing and exited 0) and a thread list naming a count twice;
// a thread list runs each Talus engine once per count.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/command_outcome.h"

namespace {

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
#endif

}  // namespace
