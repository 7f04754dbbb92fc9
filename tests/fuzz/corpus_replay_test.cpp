// Every seed and every former crash of the fuzz targets, replayed through
// the targets' own invariant checks (fuzz/fuzz_checks.h): a hull is valid
// and holds its input, or the builder refuses cleanly; the point reader
// yields finite points or a short, printable, file-naming error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_checks.h"
#include "harness_checks.h"
#include "pair_sat_checks.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"

namespace talus::fuzz {
namespace corpus_replay_test {

namespace fs = std::filesystem;

std::vector<fs::path> CorpusFiles(const std::string& target) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(TALUS_TEST_DATA_DIR) / "fuzz" / target)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string Bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(FuzzCorpus, EveryHullBuilderInputKeepsTheInvariants) {
  const auto files = CorpusFiles("hull_builder");
  ASSERT_GE(files.size(), 10u);
  for (const auto& file : files) {
    const std::string bytes = Bytes(file);
    const auto points = DecodeHullInput(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
    EXPECT_EQ(CheckHullBuild(points), "") << file.filename();
  }
}

TEST(FuzzCorpus, EveryPointFileInputKeepsTheInvariants) {
  const auto files = CorpusFiles("point_file");
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) EXPECT_EQ(CheckPointFileParse(Bytes(file)), "") << file.filename();
}

TEST(FuzzCorpus, EveryPairSatInputAgreesWithTheBruteForce) {
  const auto files = CorpusFiles("pair_sat");
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) {
    const std::string bytes = Bytes(file);
    const auto input = DecodePairInput(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
    EXPECT_EQ(CheckPairSat(input), "") << file.filename();
  }
}

TEST(FuzzCorpus, EveryScenarioLoaderInputRoundTrips) {
  const auto files = CorpusFiles("scenario_loader");
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) EXPECT_EQ(CheckScenarioRoundTrip(Bytes(file)), "") << file.filename();
}

TEST(FuzzCorpus, EveryShardMergeInputKeepsTheInvariants) {
  const auto files = CorpusFiles("shard_merge");
  ASSERT_GE(files.size(), 3u);
  for (const auto& file : files) EXPECT_EQ(CheckShardMerge(Bytes(file)), "") << file.filename();
}

// Every shipped scenario file saves and reloads to the same model (the
// fuzz target's invariant on the files users actually write), and the
// check notices a changed field.
TEST(ScenarioWriter, EveryShippedScenarioRoundTrips) {
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(TALUS_SCENARIO_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "schema.json") continue;
    ++files;
    EXPECT_EQ(CheckScenarioRoundTrip(Bytes(entry.path())), "") << entry.path();
  }
  EXPECT_GE(files, 15);
  auto runs = harness::LoadScenarioFile(std::string(TALUS_SCENARIO_DIR) + "/stacking/hull_rest.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  harness::Scenario changed = runs.Value().front().scenario;
  EXPECT_EQ(ScenarioDifference(runs.Value().front().scenario, changed), "");
  changed.bodies.back().friction = std::nextafter(changed.bodies.back().friction, 1.0);
  EXPECT_NE(ScenarioDifference(runs.Value().front().scenario, changed), "");
}

// The decoder's modes do what fuzz_checks.h says (a mode that silently
// produced nothing would leave the target fuzzing only the raw mode).
TEST(FuzzCorpus, HullInputModesProduceTheirShapes) {
  std::vector<std::uint8_t> data = {1, 20};  // near-coincident, radius 2^-20
  const double values[] = {5.0, 5.0, 5.0, 0.25, -0.5, 0.75, 3.5, 1e300, -2.25};
  const auto* raw = reinterpret_cast<const std::uint8_t*>(values);
  data.insert(data.end(), raw, raw + sizeof(values));
  auto points = DecodeHullInput(data);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], Vec3(5, 5, 5));
  EXPECT_EQ(points[1], Vec3(5, 5, 5) + std::ldexp(1.0, -20) * Vec3(0.25, -0.5, 0.75));
  data[0] = 4;  // duplicates of the raw points
  data.erase(data.begin() + 1);
  EXPECT_EQ(DecodeHullInput(data).size(), 9u);
}

}  // namespace corpus_replay_test
}  // namespace talus::fuzz
