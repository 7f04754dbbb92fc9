// `talus-testbed merge` refuses a shard file whose contents were edited
// after `sweep --shard` wrote it (a measured value, a verdict, a step
// count, a time step, a backend, a trajectory point): each shard carries
// the digest of its payload, and the error names the file. It refuses one
// job in two shard files, and `report` a results file with one job twice;
// a shard of the version before the digest is refused as older. The
// shards are written by the real command on tests/data/shards/tiny_fall
// (two time steps, two shards, the talus backend: milliseconds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/shards.h"
#include "testbed/testbed_command.h"

namespace talus::harness {
namespace shard_digest_test {

#ifdef TALUS_TESTBED_BINARY

namespace fs = std::filesystem;
using testing_support::Contains;
using testing_support::RunTestbed;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Plain string edits (std::regex trips GCC 12's -Wmaybe-uninitialized in
// the sanitizer build, and these edits need no more than this).

// `text` with every `from` replaced by `to`.
std::string ReplaceAll(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// `text` with its first `key` and the run of `valueChars` after it (none
// when empty) replaced by `replacement`; unchanged when `key` is absent.
std::string ReplaceFirstValue(std::string text, const std::string& key, const std::string& valueChars,
                              const std::string& replacement) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return text;
  std::size_t end = at + key.size();
  if (!valueChars.empty()) end = std::min(text.find_first_not_of(valueChars, end), text.size());
  text.replace(at, end - at, replacement);
  return text;
}

// `text` without its `"payloadDigest": "...",` line.
std::string WithoutDigestLine(std::string text) {
  const std::size_t at = text.find("\"payloadDigest\": \"");
  if (at == std::string::npos) return text;
  const std::size_t lineStart = text.rfind('\n', at);
  const std::size_t close = text.find('"', at + std::string("\"payloadDigest\": \"").size());
  if (lineStart == std::string::npos || close == std::string::npos || close + 1 >= text.size() ||
      text[close + 1] != ',') {
    return text;
  }
  text.erase(lineStart, close + 2 - lineStart);
  return text;
}

class ShardDigest : public testing::Test {
 protected:
  void SetUp() override {
    folder = fs::temp_directory_path() / (std::string("talus_shard_digest_") +
                                          testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder);
    fs::create_directories(folder);
    for (const char* shard : {"0/2", "1/2"}) {
      const auto outcome = RunTestbed("sweep --quiet --deterministic " + std::string(TALUS_TEST_DATA_DIR) +
                                      "/shards/tiny_fall.json -b talus --time-step 0.01,0.02 --iterations 10 "
                                      "--shard " +
                                      shard + " -o " + folder.string());
      ASSERT_EQ(outcome.code, 0) << outcome.output;
    }
    first = folder / "shard-0-of-2.json";
    second = folder / "shard-1-of-2.json";
    ASSERT_TRUE(fs::exists(first) && fs::exists(second));
  }
  void TearDown() override { fs::remove_all(folder); }

  // `merge` of both shards after the first `key` in the first shard's
  // text, with the run of `valueChars` after it, became `replacement`.
  testing_support::CommandOutcome MergeEdited(const std::string& key, const std::string& valueChars,
                                              const std::string& replacement) {
    const std::string text = ReadText(first);
    const std::string edited = ReplaceFirstValue(text, key, valueChars, replacement);
    EXPECT_NE(edited, text) << "key " << key << " not in the shard";
    WriteText(first, edited);
    return Merge();
  }
  testing_support::CommandOutcome Merge() {
    return RunTestbed("merge " + first.string() + " " + second.string() + " -o " + (folder / "out").string());
  }
  // Whether `outcome` is merge's refusal of the first shard for its digest.
  void ExpectDigestRefusal(const testing_support::CommandOutcome& outcome) {
    EXPECT_EQ(outcome.code, 2) << outcome.output;  // bad input
    EXPECT_TRUE(
        Contains(outcome.output, first.string() + ": shard file: the digest does not match its contents"))
        << outcome.output;
  }

  fs::path folder, first, second;
};

TEST_F(ShardDigest, UneditedShardsMerge) {
  const auto outcome = Merge();
  EXPECT_EQ(outcome.code, 0) << outcome.output;
  EXPECT_TRUE(Contains(ReadText(first), "\"payloadDigest\": \"fnv1a64:")) << ReadText(first);
}

// Re-indenting the file (the digest is of the canonical dump) is no edit.
TEST_F(ShardDigest, ReindentedShardsStillMerge) {
  const std::string text = ReadText(first);
  WriteText(first, ReplaceAll(text, "\n  ", "\n    "));
  const auto outcome = Merge();
  EXPECT_EQ(outcome.code, 0) << outcome.output;
}

TEST_F(ShardDigest, AnEditedMeasuredValueIsRefusedNamingTheFile) {
  ExpectDigestRefusal(MergeEdited("\"measured\": ", "-+0123456789.eE", "\"measured\": 0.125"));
}

TEST_F(ShardDigest, AFlippedVerdictIsRefusedNamingTheFile) {
  const bool passes = Contains(ReadText(first), "\"pass\": true");
  ExpectDigestRefusal(passes ? MergeEdited("\"pass\": true", "", "\"pass\": false")
                             : MergeEdited("\"pass\": false", "", "\"pass\": true"));
}

TEST_F(ShardDigest, AChangedStepCountIsRefusedNamingTheFile) {
  ExpectDigestRefusal(MergeEdited("\"steps\": ", "0123456789", "\"steps\": 7"));
}

TEST_F(ShardDigest, AChangedTimeStepIsRefusedNamingTheFile) {
  ExpectDigestRefusal(MergeEdited("\"timeStep\": ", "-+0123456789.eE", "\"timeStep\": 0.005"));
}

// A backend renamed in the file would otherwise be a run of another
// engine (and, renamed to one it already has, a duplicated job).
TEST_F(ShardDigest, AChangedBackendIsRefusedNamingTheFile) {
  ExpectDigestRefusal(MergeEdited("\"backend\": \"talus\"", "", "\"backend\": \"bullet\""));
}

TEST_F(ShardDigest, AChangedTrajectoryPointIsRefusedNamingTheFile) {
  const std::string text = ReadText(first);
  // The plot series are the trajectory a shard keeps (a sweep's plot has
  // two points): the first number of its heights, one digit changed.
  const auto at = text.find("\"heights\"");
  ASSERT_NE(at, std::string::npos) << text;
  const auto digit = text.find_first_of("123456789", at);
  ASSERT_NE(digit, std::string::npos);
  std::string edited = text;
  edited[digit] = edited[digit] == '9' ? '8' : static_cast<char>(edited[digit] + 1);
  WriteText(first, edited);
  ExpectDigestRefusal(Merge());
}

TEST_F(ShardDigest, AShardWithoutADigestIsRefusedAsOlder) {
  const std::string text = ReadText(first);
  const std::string old = ReplaceAll(WithoutDigestLine(text), "\"version\": 3", "\"version\": 2");
  WriteText(first, old);
  auto outcome = Merge();
  EXPECT_EQ(outcome.code, 2) << outcome.output;  // bad input
  EXPECT_TRUE(Contains(outcome.output, first.string() +
                                           ": shard file: version 2, expected 3 (written by an "
                                           "older talus-testbed: its shard files carry no digest"))
      << outcome.output;
  // This version without its digest: refused too, not merged unchecked.
  WriteText(first, WithoutDigestLine(text));
  outcome = Merge();
  EXPECT_EQ(outcome.code, 2) << outcome.output;  // bad input
  EXPECT_TRUE(Contains(outcome.output, first.string() + ": shard file: missing string \"payloadDigest\""))
      << outcome.output;
}

// One job in two shard files, each with the right digest of its own
// contents (as a buggy or hand-made writer would leave them): refused,
// naming both files and the job.
TEST_F(ShardDigest, OneJobInTwoShardsIsRefusedNamingBothFiles) {
  auto mine = ShardFromJson(ReadText(first));
  auto theirs = ShardFromJson(ReadText(second));
  ASSERT_TRUE(mine && theirs);
  ASSERT_FALSE(mine.Value().results.results.empty() || theirs.Value().results.results.empty());
  ShardFile copy = mine.Value();
  const RunResult& taken = theirs.Value().results.results.front();
  copy.results.results.front().runId = taken.runId;
  WriteText(first, ShardToJson(copy));  // through the writer: its digest is right
  const auto outcome = Merge();
  EXPECT_EQ(outcome.code, 2) << outcome.output;  // bad input
  EXPECT_TRUE(Contains(outcome.output, "run \"" + taken.runId + "\" on backend \"talus\" is in both " +
                                           first.string() + " and " + second.string()))
      << outcome.output;
}

// A results file with one (run, backend) twice: `report` refuses it.
TEST_F(ShardDigest, AResultsFileWithAJobTwiceIsRefusedByReport) {
  ASSERT_EQ(Merge().code, 0);
  const fs::path results = folder / "out" / "results.json";
  auto read = ReadResultsFile(results);
  ASSERT_TRUE(read) << read.GetError().message;
  ResultsFile twice = read.Value();
  ASSERT_GE(twice.results.size(), 2u);
  twice.results.push_back(twice.results.front());
  const fs::path doubled = folder / "doubled" / "results.json";
  fs::create_directories(doubled.parent_path());
  ASSERT_TRUE(WriteResultsFile(doubled, twice));
  const auto outcome = RunTestbed("report " + doubled.string() + " -o " + (folder / "report").string());
  EXPECT_EQ(outcome.code, 2) << outcome.output;  // bad input
  EXPECT_TRUE(Contains(outcome.output, doubled.string() + ": run \"" + twice.results.front().runId +
                                           "\" on backend \"talus\" appears twice (results 0 and " +
                                           std::to_string(twice.results.size() - 1) + ")"))
      << outcome.output;
  EXPECT_FALSE(fs::exists(folder / "report" / "report.html"));
}

#endif  // TALUS_TESTBED_BINARY

}  // namespace shard_digest_test
}  // namespace talus::harness
