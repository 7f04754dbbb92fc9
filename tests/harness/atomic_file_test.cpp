// WriteFileAtomically: a file is replaced whole or not at all, failures
// leave no temporary behind, and concurrent writers never interleave.
#include "talus/harness/support/atomic_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace talus::harness {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("talus_atomic_file_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string Read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Names in `dir` other than `keep`: leftovers of a write.
std::vector<std::string> Others(const fs::path& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != keep) names.push_back(entry.path().filename().string());
  }
  return names;
}

TEST(AtomicFile, ReplacesAnExistingFileWholeAndLeavesNoTemporary) {
  const fs::path dir = FreshDir("replace");
  std::ofstream(dir / "results.json") << "old contents";
  ASSERT_TRUE(WriteFileAtomically(dir / "results.json", "new contents\n"));
  EXPECT_EQ(Read(dir / "results.json"), "new contents\n");
  EXPECT_TRUE(Others(dir, "results.json").empty());
}

TEST(AtomicFile, AFailedRenameLeavesTheTargetAsItWasAndNoTemporary) {
  // The target is a non-empty folder: the temporary is written, then the
  // rename fails. (A read-only folder would not fail here: tests may run as
  // root.)
  const fs::path dir = FreshDir("rename_fails");
  fs::create_directories(dir / "results.json");
  std::ofstream(dir / "results.json" / "inside") << "kept";
  const auto written = WriteFileAtomically(dir / "results.json", "new contents");
  ASSERT_FALSE(written);
  EXPECT_NE(written.GetError().message.find((dir / "results.json").string() + ": cannot write ("),
            std::string::npos)
      << written.GetError().message;
  EXPECT_EQ(Read(dir / "results.json" / "inside"), "kept");
  EXPECT_TRUE(Others(dir, "results.json").empty());
}

TEST(AtomicFile, AMissingFolderIsAnErrorNamingThePath) {
  const fs::path dir = FreshDir("missing");
  const auto written = WriteFileAtomically(dir / "absent" / "report.html", "x");
  ASSERT_FALSE(written);
  EXPECT_NE(written.GetError().message.find("report.html: cannot write"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "absent"));
}

TEST(AtomicFile, TemporaryNamesAreUniqueAndInTheSameFolder) {
  const fs::path target = fs::path("out") / "results.json";
  const fs::path a = TemporarySibling(target);
  const fs::path b = TemporarySibling(target);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.parent_path(), target.parent_path());
  EXPECT_EQ(a.filename().string().rfind("results.json.tmp-", 0), 0u);
}

TEST(AtomicFile, ConcurrentWritersOfOneFileNeverInterleave) {
  // Eight writers, each writing its own 256 kB text twenty times: whenever
  // the file is read it is exactly one writer's text.
  const fs::path dir = FreshDir("concurrent");
  const fs::path target = dir / "results.json";
  constexpr int kWriters = 8;
  std::vector<std::string> texts;
  for (int w = 0; w < kWriters; ++w) texts.emplace_back(std::size_t{1} << 18, static_cast<char>('a' + w));
  std::vector<std::thread> threads;
  std::vector<int> failures(kWriters, 0);
  for (int w = 0; w < kWriters; ++w) {
    threads.emplace_back([&, w] {
      for (int k = 0; k < 20; ++k) failures[w] += WriteFileAtomically(target, texts[w]) ? 0 : 1;
    });
  }
  int mixed = 0;
  for (int k = 0; k < 50; ++k) {
    const std::string seen = Read(target);
    if (!seen.empty() && std::find(texts.begin(), texts.end(), seen) == texts.end()) ++mixed;
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(mixed, 0);
  for (int w = 0; w < kWriters; ++w) EXPECT_EQ(failures[w], 0);
  EXPECT_NE(std::find(texts.begin(), texts.end(), Read(target)), texts.end());
  EXPECT_TRUE(Others(dir, "results.json").empty());
}

}  // namespace
}  // namespace talus::harness
