// The soak suite's shortened form, run in CI's Release tree (label slow;
// the sanitizer tree skips it): every family for 2000 steps on every
// backend and the abuse cases (soak_cases.h) for 300 steps, 100
// coincident boxes for 30 steps. The same verdict as the full suite.
#include <gtest/gtest.h>

#include "soak_cases.h"
#include "talus/reference/all_backends.h"

namespace talus::harness::soak {
namespace soak_short_test {

RunnerOptions Options() {
  RunnerOptions options;
  options.backends = reference::AllBackends().Names();
  options.jobs = 2;
  options.plotPoints = 2;
  options.maxSamples = 50;
  return options;
}

void ExpectSurvival(const std::vector<Run>& runs) {
  auto results = RunAll(reference::AllBackends(), runs, Options());
  ASSERT_TRUE(results) << results.GetError().message;
  for (const RunResult& result : results.Value()) EXPECT_EQ(SoakVerdict(result), "");
}

TEST(SoakShort, EveryFamilyOnEveryBackend) { ExpectSurvival(FamilyRuns(2000)); }

TEST(SoakShort, AbuseCasesOnEveryBackend) { ExpectSurvival(AbuseRuns(300, 100, 30)); }

// A soak finding: the tuned ODE configurations (dHashSpace) aborted the
// whole process on an internal assertion once a body flew past about 2.7e8
// m (its int cell numbers overflow), well inside the 1e9 m every engine
// is stepped to. Now the ODE backend ends that run with the body named.
TEST(SoakShort, OdeHashSpaceEndsTheRunOfAFarBodyInsteadOfAborting) {
  harness::Run run = CoincidentBoxes(1, 5);
  run.id = "far_box";
  run.scenario.name = run.id;
  run.scenario.bodies[1].position = Vec3(2e8, 0.5, 0);
  RunnerOptions options = Options();
  options.backends = {"ode-step-tuned", "ode-quickstep-tuned", "ode-step"};
  auto results = RunAll(reference::AllBackends(), {run}, options);
  ASSERT_TRUE(results) << results.GetError().message;
  ASSERT_EQ(results.Value().size(), 3u);
  for (int i = 0; i < 2; ++i) {
    const RunResult& result = results.Value()[static_cast<std::size_t>(i)];
    EXPECT_EQ(SoakVerdict(result), "");
    EXPECT_NE(result.error.find("body \"box0\" is beyond "), std::string::npos) << result.error;
    EXPECT_NE(result.error.find("dHashSpace"), std::string::npos) << result.error;
  }
  EXPECT_EQ(results.Value()[2].error, "");  // dSimpleSpace has no such bound
}

// The verdict itself: what it accepts and refuses.
TEST(SoakShort, VerdictNeedsTheStepEngineAndBody) {
  RunResult result;
  result.runId = "spin_1e6";
  result.backend = "bullet";
  result.steps = 10;
  EXPECT_EQ(SoakVerdict(result), "");
  result.error = "step 812: bullet: body \"spinner\": non-finite position (nan, nan, nan)";
  EXPECT_EQ(SoakVerdict(result), "");
  result.error = "step 812: bullet: non-finite position (nan, nan, nan)";
  EXPECT_NE(SoakVerdict(result), "");
  result.error = "step 812: ode-step: body \"spinner\": non-finite position (nan, nan, nan)";
  EXPECT_NE(SoakVerdict(result), "");
  result.error = "something went wrong";
  EXPECT_NE(SoakVerdict(result), "");
  result.backend = "mujoco-tuned";
  result.error = "mujoco: the world needs at least 1425 MB of mjData";
  EXPECT_EQ(SoakVerdict(result), "");
  result.error = "bullet: the world needs more";
  EXPECT_NE(SoakVerdict(result), "");
  result.backend = "talus";
  result.error = "step 3: talus: body \"spinner\": non-finite position (nan, nan, nan)";
  EXPECT_NE(SoakVerdict(result), "");
  result.error = "step 3: talus: World::Step refused: body \"spinner\" is beyond 1e9 m";
  EXPECT_EQ(SoakVerdict(result), "");
}

}  // namespace soak_short_test
}  // namespace talus::harness::soak
