// talus-scenes refuses a parameter of 0 (which meant "the default" inside
// the program and was silently accepted) and an engine list naming no
// engine (which ran nothing and exited 0).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

#ifdef TALUS_SCENES_BINARY
struct Outcome {
  int code = -1;
  std::string output;
};

Outcome Execute(const std::string& arguments) {
  // One log per test and process: ctest runs these tests in parallel.
  const auto log = std::filesystem::temp_directory_path() /
                   (std::string("talus_scenes_command_") +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                    std::to_string(::getpid()) + ".log");
  const int status = std::system(
      (std::string(TALUS_SCENES_BINARY) + " " + arguments + " >" + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
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
