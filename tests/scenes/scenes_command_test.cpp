// talus-scenes refuses a parameter of 0 (which meant "the default" inside
// the program and was silently accepted) and an engine list naming no
// engine (which ran nothing and exited 0).
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
#endif

}  // namespace
