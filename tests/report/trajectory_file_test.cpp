// On disk the results are two files (results_file.h): results.json without
// the trajectories, and the trajectory file beside it with each result's
// plot series and replay, one line per result. They are written as one
// set and read back to the same results; a trajectory file that does not
// belong to its results file is refused with the place named; the one-text
// form (ResultsToJson, how results.json was written before) still reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/scratch_files.h"
#include "talus/harness/run/results_file.h"

namespace talus::harness {
namespace trajectory_file_test {

namespace fs = std::filesystem;

// Two results of one run, the second with a two-frame replay of one box.
ResultsFile TwoResultsOneReplay() {
  ResultsFile file;
  file.backends = {"talus", "bullet"};
  file.deterministic = true;
  for (const char* backend : {"talus", "bullet"}) {
    RunResult r;
    r.scenario = "box_rest";
    r.file = "box_rest.json";
    r.runId = "box_rest";
    r.backend = backend;
    r.timeStep = 1.0 / 60;
    r.steps = 2;
    r.bodyNames = {"box"};
    r.series.time = {0.0, 1.0 / 60};
    r.series.heights = {{0.5, 0.49999999999}};
    r.series.energy = {4.905, 4.904999999};
    file.results.push_back(r);
  }
  Replay& replay = file.results[1].replay;
  ReplayShape box;
  box.halfExtents = Vec3(0.5, 0.5, 0.5);
  replay.shapes.push_back(box);
  replay.counterNames = {"contact points"};
  replay.frames.push_back({0.0, {Vec3(0, 0.5, 0)}, {Quat::Identity()}, {}, {}});
  replay.frames.push_back({1.0 / 60, {Vec3(0, 0.49999999999, 0)}, {Quat::Identity()}, {}, {4.0}});
  return file;
}

std::string Read(const fs::path& path) { return testing_support::ReadWholeFile(path); }

fs::path FreshDir(const std::string& name) {
  return testing_support::FreshScratchDir("trajectory_file_" + name);
}

TEST(TrajectoryFile, ResultsJsonHoldsNoSeriesAndNoFrame) {
  const fs::path dir = FreshDir("split");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", TwoResultsOneReplay()));
  EXPECT_EQ(TrajectoryFilePath(dir / "results.json"), dir / "results.trajectories.json");
  const std::string results = Read(dir / "results.json");
  EXPECT_NE(results.find("\"trajectories\": 2,"), std::string::npos) << results;
  EXPECT_EQ(results.find("\"series\""), std::string::npos) << results;
  EXPECT_EQ(results.find("\"frames\""), std::string::npos) << results;
  const std::string trajectories = Read(dir / "results.trajectories.json");
  EXPECT_EQ(trajectories.rfind("{\"format\":\"talus-testbed-trajectories\",\"version\":1,\"resolution\":"
                               "\"display\",\"replays\":1,\"trajectories\":[\n"
                               "{\"result\":0,\"run\":\"box_rest\",\"backend\":\"talus\",\"series\":",
                               0),
            0u)
      << trajectories;
  EXPECT_NE(trajectories.find("\n{\"result\":1,\"run\":\"box_rest\",\"backend\":\"bullet\",\"series\":"),
            std::string::npos)
      << trajectories;
  // The replays have their own file: one line per replayed result.
  EXPECT_EQ(trajectories.find("\"frames\""), std::string::npos) << trajectories;
  EXPECT_EQ(ReplayFilePath(dir / "results.json"), dir / "results.replays.json");
  const std::string replays = Read(dir / "results.replays.json");
  EXPECT_EQ(replays.rfind("{\"format\":\"talus-testbed-replays\",\"version\":1,\"replays\":[\n"
                          "{\"result\":1,\"run\":\"box_rest\",\"backend\":\"bullet\",\"replay\":{",
                          0),
            0u)
      << replays;
}

TEST(TrajectoryFile, WrittenFullAndReadBackToTheSameResultsBitForBit) {
  ResultsFile file = TwoResultsOneReplay();
  file.fullTrajectories = true;  // talus-testbed run --full-trajectories
  const fs::path dir = FreshDir("round_trip");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", file));
  auto read = ReadResultsFile(dir / "results.json");
  ASSERT_TRUE(read) << read.GetError().message;
  // The one-text form holds every number: equal texts, equal results.
  EXPECT_EQ(ResultsToJson(read.Value()), ResultsToJson(file));
  ASSERT_EQ(read.Value().results[1].replay.frames.size(), 2u);
  EXPECT_TRUE(read.Value().results[0].replay.frames.empty());
}

// By default the trajectory file holds the display form (display_trajectory.h):
// results.json is the same bytes as with the full form (the metrics are
// never computed from it), the numbers are rounded, and reading the file and
// writing it again (a report beside its run) gives the same bytes.
TEST(TrajectoryFile, TheDefaultDisplayFormChangesOnlyTheTrajectories) {
  ResultsFile full = TwoResultsOneReplay();
  full.fullTrajectories = true;
  const fs::path fullDir = FreshDir("display_full");
  ASSERT_TRUE(WriteResultsFile(fullDir / "results.json", full));
  const fs::path dir = FreshDir("display");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", TwoResultsOneReplay()));
  EXPECT_EQ(Read(dir / "results.json"), Read(fullDir / "results.json"));
  auto read = ReadResultsFile(dir / "results.json");
  ASSERT_TRUE(read) << read.GetError().message;
  EXPECT_FALSE(read.Value().fullTrajectories);
  // 0.49999999999 over a range of 1e-11 keeps its digits; the replay's
  // position is rounded to 0.1 mm, the time to 1 us.
  EXPECT_EQ(read.Value().results[0].series.heights[0][1], 0.49999999999);
  EXPECT_EQ(read.Value().results[0].series.time[1], 0.016667);
  EXPECT_EQ(read.Value().results[1].replay.frames[1].positions[0].y(), 0.5);
  const fs::path again = FreshDir("display_again");
  ASSERT_TRUE(WriteResultsFile(again / "results.json", read.Value()));
  EXPECT_EQ(Read(again / "results.trajectories.json"), Read(dir / "results.trajectories.json"));
  // The full form, read back, is written full again.
  auto readFull = ReadResultsFile(fullDir / "results.json");
  ASSERT_TRUE(readFull) << readFull.GetError().message;
  EXPECT_TRUE(readFull.Value().fullTrajectories);
}

TEST(TrajectoryFile, AnUnknownResolutionIsRefusedWithThePlace) {
  const fs::path dir = FreshDir("resolution");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", TwoResultsOneReplay()));
  std::string trajectories = Read(dir / "results.trajectories.json");
  trajectories.replace(trajectories.find("\"display\""), 9, "\"coarse\"");
  auto read = ResultsFromJson(Read(dir / "results.json"), trajectories);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.GetError().message,
            "trajectory file: /resolution: \"coarse\", expected \"full\" or \"display\"");
}

TEST(TrajectoryFile, AMissingTrajectoryFileIsNamed) {
  const fs::path dir = FreshDir("missing");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", TwoResultsOneReplay()));
  fs::remove(dir / "results.trajectories.json");
  auto read = ReadResultsFile(dir / "results.json");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.GetError().message, (dir / "results.json").string() + ": its trajectories: " +
                                         (dir / "results.trajectories.json").string() +
                                         ": cannot read the trajectory file");
}

TEST(TrajectoryFile, AMissingOrForeignReplayFileIsNamed) {
  const fs::path dir = FreshDir("replays");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", TwoResultsOneReplay()));
  const std::string replays = Read(dir / "results.replays.json");
  fs::remove(dir / "results.replays.json");
  auto read = ReadResultsFile(dir / "results.json");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.GetError().message, (dir / "results.json").string() +
                                         ": its replays: " + (dir / "results.replays.json").string() +
                                         ": cannot read the replay file");
  std::string other = replays;
  other.replace(other.find("\"result\":1"), 10, "\"result\":0");
  auto foreign = ResultsFromJson(Read(dir / "results.json"), Read(dir / "results.trajectories.json"), other);
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.GetError().message,
            "replay file: /replays/0: not the replay of result 0 (box_rest with talus)");
  auto none = ResultsFromJson(Read(dir / "results.json"), Read(dir / "results.trajectories.json"),
                              "{\"format\":\"talus-testbed-replays\",\"version\":1,\"replays\":[]}");
  ASSERT_FALSE(none);
  EXPECT_EQ(none.GetError().message, "replay file: /replays: 0 replays where the trajectory file says 1");
}

TEST(TrajectoryFile, AnotherResultsTrajectoriesAreRefusedWithThePlace) {
  const ResultsFile file = TwoResultsOneReplay();
  const fs::path dir = FreshDir("mismatch");
  ASSERT_TRUE(WriteResultsFile(dir / "results.json", file));
  std::string trajectories = Read(dir / "results.trajectories.json");
  trajectories.replace(trajectories.find("\"backend\":\"bullet\""), 18, "\"backend\":\"ode-st\"");
  auto read = ResultsFromJson(Read(dir / "results.json"), trajectories);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.GetError().message,
            "trajectory file: /trajectories/1: not the trajectory of result 1 (box_rest with bullet)");
  // The file form without its trajectory file is not a results file on its own.
  auto alone = ResultsFromJson(Read(dir / "results.json"));
  ASSERT_FALSE(alone);
  EXPECT_EQ(alone.GetError().message, "its trajectories: no trajectory file was given");
}

TEST(TrajectoryFile, TheOneTextFormStillReads) {
  const ResultsFile file = TwoResultsOneReplay();
  auto read = ResultsFromJson(ResultsToJson(file));
  ASSERT_TRUE(read) << read.GetError().message;
  EXPECT_EQ(ResultsToJson(read.Value()), ResultsToJson(file));
  const fs::path dir = FreshDir("one_text");
  std::ofstream(dir / "results.json") << ResultsToJson(file);
  auto fromDisk = ReadResultsFile(dir / "results.json");
  ASSERT_TRUE(fromDisk) << fromDisk.GetError().message;
  EXPECT_EQ(ResultsToJson(fromDisk.Value()), ResultsToJson(file));
}

}  // namespace trajectory_file_test
}  // namespace talus::harness
