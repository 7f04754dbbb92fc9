// WriteFilesAtomically: a set of outputs is written whole or not at all; a
// folder, a full device or a missing folder fails naming the file and the
// reason, and leaves the regular files of the set as they were.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/scratch_files.h"
#include "talus/harness/support/atomic_file.h"

namespace talus::harness {
namespace atomic_file_set_test {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) { return testing_support::FreshScratchDir("atomic_set_" + name); }

std::string Read(const fs::path& path) { return testing_support::ReadWholeFile(path); }

std::vector<std::string> Names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFileSet, WritesEveryFileAndLeavesNoTemporary) {
  const fs::path dir = FreshDir("all");
  std::ofstream(dir / "a.json") << "old";
  const std::vector<FileText> files = {{dir / "a.json", "new a"}, {dir / "b.md", "new b"}};
  ASSERT_TRUE(WriteFilesAtomically(files));
  EXPECT_EQ(Read(dir / "a.json"), "new a");
  EXPECT_EQ(Read(dir / "b.md"), "new b");
  EXPECT_EQ(Names(dir), (std::vector<std::string>{"a.json", "b.md"}));
}

TEST(AtomicFileSet, AFullDeviceLeavesNoFileOfTheSet) {
  // /dev/full: every write fails with ENOSPC. The device is written
  // directly, never renamed over (tests may run as root, and a rename
  // would replace the device with a plain file).
  const fs::path dir = FreshDir("full");
  std::ofstream(dir / "kept.json") << "old";
  const std::vector<FileText> files = {
      {dir / "new.json", "a"}, {dir / "kept.json", "b"}, {"/dev/full", "markdown"}};
  const auto written = WriteFilesAtomically(files);
  ASSERT_FALSE(written);
  EXPECT_NE(written.GetError().message.find("/dev/full: cannot write ("), std::string::npos)
      << written.GetError().message;
  EXPECT_NE(written.GetError().message.find("No space left on device"), std::string::npos)
      << written.GetError().message;
  EXPECT_EQ(Names(dir), std::vector<std::string>{"kept.json"});
  EXPECT_EQ(Read(dir / "kept.json"), "old");
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(AtomicFileSet, ADeviceThatTakesTheTextIsWrittenDirectly) {
  const fs::path dir = FreshDir("null");
  const std::vector<FileText> files = {{"/dev/null", "discarded"}, {dir / "a.json", "a"}};
  ASSERT_TRUE(WriteFilesAtomically(files));
  EXPECT_EQ(Read(dir / "a.json"), "a");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(AtomicFileSet, AFolderAsATargetIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = FreshDir("folder");
  fs::create_directories(dir / "report");
  const std::vector<FileText> files = {{dir / "a.json", "a"}, {dir / "report", "b"}};
  const auto written = WriteFilesAtomically(files);
  ASSERT_FALSE(written);
  EXPECT_EQ(written.GetError().message, (dir / "report").string() + ": cannot write (it is a folder)");
  EXPECT_EQ(Names(dir), std::vector<std::string>{"report"});
}

TEST(AtomicFileSet, AMissingFolderFailsTheSetAndRemovesTheTemporariesWritten) {
  const fs::path dir = FreshDir("missing");
  const std::vector<FileText> files = {{dir / "a.json", "a"}, {dir / "no" / "b.md", "b"}};
  const auto written = WriteFilesAtomically(files);
  ASSERT_FALSE(written);
  EXPECT_NE(written.GetError().message.find((dir / "no" / "b.md").string() + ": cannot write ("),
            std::string::npos);
  EXPECT_TRUE(Names(dir).empty());
}

TEST(AtomicFileSet, OnePathNamedTwiceIsRefused) {
  const fs::path dir = FreshDir("twice");
  const std::vector<FileText> files = {{dir / "a.json", "a"}, {dir / "." / "a.json", "b"}};
  const auto written = WriteFilesAtomically(files);
  ASSERT_FALSE(written);
  EXPECT_NE(written.GetError().message.find("named twice"), std::string::npos);
  EXPECT_TRUE(Names(dir).empty());
}

}  // namespace atomic_file_set_test
}  // namespace talus::harness
