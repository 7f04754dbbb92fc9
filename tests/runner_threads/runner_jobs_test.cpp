// The testbed's runner with its own threads (jobs) around Talus worlds with
// theirs (TalusBackendOptions::threads): results.json is byte-identical at
// 1, 2 and 8 jobs, and a Talus world's results do not depend on its thread
// count. Only the Talus backends are registered, so the ThreadSanitizer
// tree builds no peer. The jobs run in this process (JobIsolation::
// InProcess), on the runner's threads, which is what ThreadSanitizer is
// here to watch; the ThreadSanitizer tree never forks a job's process
// (tests/testbed/isolation_test.cpp checks the processes give the same
// bytes).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness {
namespace runner_jobs_test {

namespace fs = std::filesystem;
// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

std::vector<Run> LoadShipped(const std::vector<std::string>& relative) {
  std::vector<fs::path> paths;
  for (const std::string& file : relative) paths.emplace_back(fs::path(TALUS_SCENARIO_DIR) / file);
  auto runs = LoadScenarios(paths);
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value() : std::vector<Run>{};
}

BackendRegistry TalusBackends(int threads) {
  BackendRegistry registry;
  reference::RegisterTalusBackends(registry, {.threads = threads});
  return registry;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

// A scratch folder of this test, removed at the end.
class ScratchFolder {
 public:
  ScratchFolder()
      : m_path(fs::temp_directory_path() /
               ("talus_runner_jobs_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    fs::remove_all(m_path);
    fs::create_directories(m_path);
  }
  ~ScratchFolder() { fs::remove_all(m_path); }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  [[nodiscard]] const fs::path& Path() const { return m_path; }

 private:
  fs::path m_path;
};

TEST(RunnerJobs, ResultsFileIsByteIdenticalAtOneTwoAndEightJobs) {
  const std::vector<ScenarioRun> runs =
      LoadShipped({"stacking/box_pyramid_4.json", "sliding/box_slide.json", "tumbling/box_free_fall.json"});
  ASSERT_FALSE(runs.empty());
  // Each world on 2 threads inside the runner's jobs: both pools at once.
  const BackendRegistry registry = TalusBackends(2);
  RunnerOptions options;
  options.backends = {"talus", "talus-split"};
  options.deterministic = true;
  options.isolation = JobIsolation::InProcess;
  const ScratchFolder scratch;
  std::string first;
  for (const int jobs : {1, 2, 8}) {
    options.jobs = jobs;
    auto results = RunAll(registry, runs, options);
    ASSERT_TRUE(results) << results.GetError().message;
    const fs::path path = scratch.Path() / ("results_" + std::to_string(jobs) + ".json");
    const auto written = WriteResultsFile(path, ResultsFile{options.backends, true, results.Value()});
    ASSERT_TRUE(written) << written.GetError().message;
    const std::string bytes = ReadBytes(path);
    ASSERT_FALSE(bytes.empty());
    for (const RunResult& result : results.Value()) EXPECT_TRUE(result.error.empty()) << result.error;
    if (first.empty()) {
      first = bytes;
      continue;
    }
    // Compared line by line so a failure names the first differing line.
    std::istringstream a(first);
    std::istringstream b(bytes);
    std::string lineA;
    std::string lineB;
    for (int line = 1; std::getline(a, lineA) && std::getline(b, lineB); ++line) {
      ASSERT_EQ(lineA, lineB) << jobs << " jobs, line " << line;
    }
    EXPECT_EQ(bytes.size(), first.size()) << jobs << " jobs";
  }
}

TEST(RunnerJobs, TalusResultsDoNotDependOnTheWorldsThreadCount) {
  const std::vector<ScenarioRun> runs =
      LoadShipped({"stacking/box_pyramid_4.json", "stacking/hull_rest.json"});
  ASSERT_FALSE(runs.empty());
  RunnerOptions options;
  options.backends = {"talus"};
  options.deterministic = true;
  options.isolation = JobIsolation::InProcess;
  options.jobs = 2;
  std::string first;
  for (const int threads : {1, 3}) {
    auto results = RunAll(TalusBackends(threads), runs, options);
    ASSERT_TRUE(results) << results.GetError().message;
    for (RunResult& result : results.Value()) {
      ASSERT_TRUE(result.error.empty()) << result.error;
      // The one recorded difference: the "threads" setting says so.
      bool listed = false;
      for (const Setting& setting : result.settings) {
        if (setting.key != "threads") continue;
        listed = true;
        EXPECT_EQ(setting.value, std::to_string(threads));
      }
      EXPECT_TRUE(listed);
      result.settings.clear();
    }
    const std::string json = ResultsToJson(ResultsFile{options.backends, true, results.Value()});
    if (first.empty()) {
      first = json;
    } else {
      EXPECT_EQ(json, first) << threads << " threads";
    }
  }
}

TEST(RunnerJobs, TalusBackendsRefuseABadThreadCountByName) {
  const std::vector<ScenarioRun> runs = LoadShipped({"tumbling/box_free_fall.json"});
  ASSERT_FALSE(runs.empty());
  const BackendRegistry registry = TalusBackends(0);
  for (const std::string name : {"talus", "talus-writeup", "talus-split"}) {
    const auto backend = registry.Create(name, runs[0]);
    ASSERT_FALSE(backend);
    EXPECT_NE(backend.GetError().message.find(name + ": WorldSettings.threads = 0 is outside [1, "),
              std::string::npos)
        << backend.GetError().message;
  }
}

}  // namespace runner_jobs_test
}  // namespace talus::harness
