// RunCommand: runs one of our programs through the shell, the way a user's
// script would, and returns its exit code and everything it printed (stdout
// and stderr together), for the tests of the command lines.
//
// The output goes through a log file named after the running test and the
// process, and the file is removed once read: ctest runs the tests of one
// binary in parallel, and a shared log let one test read another's output.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace talus::testing_support {

struct CommandOutcome {
  int code = -1;       ///< the exit status; -1 when the program did not exit normally
  std::string output;  ///< stdout and stderr together
};

inline CommandOutcome RunCommand(const std::string& commandLine) {
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() /
      (std::string("talus_command_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
       std::to_string(::getpid()) + ".log");
  const int status = std::system((commandLine + " >" + log.string() + " 2>&1").c_str());
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace talus::testing_support
