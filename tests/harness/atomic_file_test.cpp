// WriteFileAtomically: a file is replaced whole or not at all, failures
// leave no temporary behind, and concurrent writers never interleave.
// WriteFilesAtomically: a set of files is replaced whole or not at all.
#include "talus/harness/support/atomic_file.h"
#include "support/scratch_files.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace talus::harness {
namespace atomic_file_test {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) { return testing_support::FreshScratchDir("atomic_file_" + name); }

std::string Read(const fs::path& path) { return testing_support::ReadWholeFile(path); }

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

TEST(AtomicFileSet, WritesEveryFileAndReplacesTheOldOnes) {
  const fs::path dir = FreshDir("set_writes");
  std::ofstream(dir / "summary.md") << "old summary";
  ASSERT_TRUE(WriteFilesAtomically({{dir / "summary.md", "new summary"}, {dir / "report.html", "<html>"}}));
  EXPECT_EQ(Read(dir / "summary.md"), "new summary");
  EXPECT_EQ(Read(dir / "report.html"), "<html>");
  std::vector<std::string> names = Others(dir, "");
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"report.html", "summary.md"}));
}

TEST(AtomicFileSet, ARenameThatFailsMidwayPutsBackTheFilesRenamedBeforeIt) {
  // The third target is a non-empty folder: every text is written, the
  // first two are renamed into place, the third rename fails. The first
  // file must be its old self again and the second, new, must be gone.
  const fs::path dir = FreshDir("set_rename_fails");
  std::ofstream(dir / "summary.md") << "old summary";
  fs::create_directories(dir / "report.html");
  std::ofstream(dir / "report.html" / "inside") << "kept";
  const auto written = WriteFilesAtomically(
      {{dir / "summary.md", "new summary"}, {dir / "results.csv", "a,b\n"}, {dir / "report.html", "<html>"}});
  ASSERT_FALSE(written);
  EXPECT_EQ(written.GetError().message.rfind((dir / "report.html").string() + ": cannot write (", 0), 0u)
      << written.GetError().message;
  EXPECT_EQ(Read(dir / "summary.md"), "old summary");
  EXPECT_FALSE(fs::exists(dir / "results.csv"));
  EXPECT_EQ(Read(dir / "report.html" / "inside"), "kept");
  std::vector<std::string> names = Others(dir, "");
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"report.html", "summary.md"}));  // no temporary, no kept copy
}

TEST(AtomicFileSet, AFullDiskChangesNoFileOfTheSet) {
  // A full disk, made in a child process by a file size limit of 64 kB
  // (writes past it fail with EFBIG once SIGXFSZ is ignored): the small
  // file fits, the large one does not, and neither target may change.
  const fs::path dir = FreshDir("set_full_disk");
  std::ofstream(dir / "summary.md") << "old summary";
  const pid_t child = ::fork();
  ASSERT_NE(child, -1);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{64 * 1024, 64 * 1024};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(3);
    const auto written = WriteFilesAtomically(
        {{dir / "summary.md", "new summary"}, {dir / "report.html", std::string(1 << 20, 'x')}});
    if (written) ::_exit(1);
    const std::string expected = (dir / "report.html").string() + ": cannot write (File too large)";
    ::_exit(written.GetError().message == expected ? 0 : 2);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  // 1: the set was written; 2: the error did not name report.html and EFBIG; 3: no limit could be set.
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(Read(dir / "summary.md"), "old summary");
  EXPECT_TRUE(Others(dir, "summary.md").empty());
}

}  // namespace atomic_file_test
}  // namespace talus::harness
