// The full soak suite (ctest label soak, `make soak`; not in `make test`):
// every scenario file of every family for 1e5 steps on every backend, and
// the abuse cases (soak_cases.h) for 1e5 steps, 1000 coincident boxes for
// 1000 steps. Every job must finish, and each that stops early must say
// which step, engine and body (SoakVerdict). Talus must stay finite.
#include <gtest/gtest.h>

#include <iostream>
#include <thread>

#include "soak_cases.h"
#include "talus/reference/all_backends.h"

namespace talus::harness::soak {
namespace soak_test {

constexpr int kSoakSteps = 100000;

RunnerOptions Options() {
  RunnerOptions options;
  options.backends = reference::AllBackends().Names();
  options.jobs = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  options.plotPoints = 2;
  options.maxSamples = 100;
  options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  return options;
}

void ExpectSurvival(const std::vector<Run>& runs) {
  auto results = RunAll(reference::AllBackends(), runs, Options());
  ASSERT_TRUE(results) << results.GetError().message;
  int stopped = 0;
  for (const RunResult& result : results.Value()) {
    EXPECT_EQ(SoakVerdict(result), "");
    if (!result.error.empty()) {
      ++stopped;
      std::cout << "stopped: " << result.runId << " " << result.backend << ": " << result.error << "\n";
    }
  }
  std::cout << results.Value().size() << " jobs, " << stopped << " stopped with a reason\n";
}

TEST(Soak, EveryFamilyFor1e5StepsOnEveryBackend) { ExpectSurvival(FamilyRuns(kSoakSteps)); }

TEST(Soak, AbuseCasesOnEveryBackend) { ExpectSurvival(AbuseRuns(kSoakSteps, 1000, 1000)); }

}  // namespace soak_test
}  // namespace talus::harness::soak
