// talus-sat-check's outputs, end to end (issue 26): all or nothing, and a
// failed output is an error naming the file and the reason, never a PASS.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/scratch_files.h"

#ifdef TALUS_SAT_CHECK_BINARY
namespace sat_check_outputs_test {

namespace fs = std::filesystem;

struct ProgramRun {
  int status = -1;
  std::string errors;  // stderr
};

// Runs the program on 14 pairs (two of each family), without timing, with
// `arguments`; stdout is discarded, stderr kept.
ProgramRun SatCheck(const std::string& arguments, const fs::path& dir) {
  const fs::path errors = dir / "stderr.txt";
  const std::string command = std::string(TALUS_SAT_CHECK_BINARY) + " --pairs 14 --repeats 0 " + arguments +
                              " > /dev/null 2> " + errors.string();
  const int raw = std::system(command.c_str());
  ProgramRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(errors);
  std::ostringstream text;
  text << in.rdbuf();
  run.errors = text.str();
  fs::remove(errors);
  return run;
}

fs::path FreshDir(const std::string& name) {
  return talus::testing_support::FreshScratchDir("sat_check_outputs_" + name);
}

TEST(SatCheckOutputs, WritesBothReportsAndPasses) {
  const fs::path dir = FreshDir("pass");
  const ProgramRun run =
      SatCheck("--json " + (dir / "s.json").string() + " --markdown " + (dir / "s.md").string(), dir);
  EXPECT_EQ(run.status, 0) << run.errors;
  EXPECT_NE(run.errors.find("PASS"), std::string::npos) << run.errors;
  EXPECT_GT(fs::file_size(dir / "s.json"), 0u);
  EXPECT_GT(fs::file_size(dir / "s.md"), 0u);
}

TEST(SatCheckOutputs, AFullDeviceIsAnErrorNamingIt) {
  const fs::path dir = FreshDir("full");
  const ProgramRun run = SatCheck("--json /dev/full", dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.errors.find("/dev/full: cannot write (No space left on device)"), std::string::npos)
      << run.errors;
  EXPECT_EQ(run.errors.find("PASS"), std::string::npos) << run.errors;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(SatCheckOutputs, AFolderNamedAsTheJsonIsAnErrorNamingIt) {
  const fs::path dir = FreshDir("folder");
  const ProgramRun run = SatCheck("--json " + dir.string(), dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.errors.find(dir.string() + ": cannot write (it is a folder)"), std::string::npos)
      << run.errors;
  EXPECT_EQ(run.errors.find("PASS"), std::string::npos) << run.errors;
}

TEST(SatCheckOutputs, AFailedMarkdownLeavesNoJsonEither) {
  const fs::path dir = FreshDir("partial");
  const ProgramRun run = SatCheck("--json " + (dir / "s.json").string() + " --markdown /dev/full", dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.errors.find("/dev/full: cannot write"), std::string::npos) << run.errors;
  EXPECT_FALSE(fs::exists(dir / "s.json"));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(SatCheckOutputs, AFullStandardOutputIsAnError) {
  const fs::path dir = FreshDir("stdout");
  const fs::path errors = dir / "stderr.txt";
  const std::string command = std::string(TALUS_SAT_CHECK_BINARY) + " --pairs 14 --repeats 0 --json " +
                              (dir / "s.json").string() + " > /dev/full 2> " + errors.string();
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 2);
  std::ifstream in(errors);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("standard output: cannot write"), std::string::npos) << text.str();
  EXPECT_FALSE(fs::exists(dir / "s.json"));
}

}  // namespace sat_check_outputs_test
#endif  // TALUS_SAT_CHECK_BINARY
