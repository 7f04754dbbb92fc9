// The accuracy gate bites: every Talus variant is gated; a truth ungated
// for one backend is still judged and reported but does not fail that
// backend's check (and only that backend's); and Talus with one piece of
// physics deliberately broken (friction 3% high, restitution 2.5% low, a
// box whose tipping threshold sits 1.5 degrees off, gravity 1% strong in a
// toss) fails the check at the shipped scenarios' tolerances, while the
// same run unbroken passes. The perturbations are the errors the old
// tolerances let through (issue 11).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "talus/harness/report/regression_check.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace {

using ScenarioRun = Run;  // gtest's Test::Run hides harness::Run inside TEST bodies

ScenarioRun LoadRun(const std::string& relative, const std::string& id) {
  auto runs = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/" + relative});
  EXPECT_TRUE(runs) << runs.GetError().message;
  for (const ScenarioRun& run : runs.Value()) {
    if (run.id == id) return run;
  }
  ADD_FAILURE() << "no run " << id << " in " << relative;
  return {};
}

// The gate's verdict on `backend` in `file`, re-derived from `run`.
CheckOutcome Recheck(const ResultsFile& file, const ScenarioRun& run, const std::string& backend) {
  auto outcomes = RecheckResults(file, {run}, {backend}, reference::AllBackends());
  EXPECT_TRUE(outcomes) << outcomes.GetError().message;
  if (!outcomes) {
    CheckOutcome refused;
    refused.problems = {"refused"};
    return refused;
  }
  return outcomes.Value().at(0);
}

ResultsFile RunOn(const ScenarioRun& run, const std::vector<std::string>& backends) {
  RunnerOptions options;
  options.backends = backends;
  options.deterministic = true;
  auto results = RunAll(reference::AllBackends(), {run}, options);
  EXPECT_TRUE(results) << results.GetError().message;
  return ResultsFile{options.backends, true, results ? results.Value() : std::vector<RunResult>{}};
}

// The gate's verdict on `run` with the Talus default backend.
CheckOutcome Check(const ScenarioRun& run) { return Recheck(RunOn(run, {"talus"}), run, "talus"); }

std::string FirstProblem(const CheckOutcome& outcome) {
  return outcome.problems.empty() ? std::string("(none)") : outcome.problems[0];
}

TEST(Gates, EveryTalusVariantIsGatedByDefault) {
  const std::vector<std::string> variants = TalusVariants(reference::AllBackends().Names());
  for (const char* name : {"talus", "talus-writeup", "talus-split"}) {
    EXPECT_NE(std::find(variants.begin(), variants.end(), name), variants.end()) << name;
  }
  for (const std::string& name : variants) {
    EXPECT_TRUE(name == "talus" || name.rfind("talus-", 0) == 0) << name;
  }
  EXPECT_EQ(TalusVariants({"bullet", "talus-x", "ode-step", "talusish"}),
            std::vector<std::string>{"talus-x"});
}

TEST(Gates, AnUngatedTruthIsJudgedAndShownButFailsOnlyTheBackendsNotListed) {
  ScenarioRun run = LoadRun("stacking/box_rest.json", "box_rest");
  ResultsFile file = RunOn(run, {"talus", "talus-writeup"});
  // Both backends' rest height measured 0.3 m off: a failure for each.
  for (RunResult& result : file.results) result.metrics.at(0).measured += 0.3;
  run.scenario.truths.at(0).ungated = {{"talus-writeup", "topples: measured 4.5 m"}};
  const CheckOutcome writeup = Recheck(file, run, "talus-writeup");
  EXPECT_TRUE(writeup.Ok()) << FirstProblem(writeup);
  // Both of the truth's metrics (height and jitter) are listed; the height's
  // verdict is recomputed from the doctored measurement.
  ASSERT_EQ(writeup.ungated.size(), 2u);
  EXPECT_NE(writeup.ungated[0].find("rest_height.height: FAIL (ungated: topples: measured 4.5 m)"),
            std::string::npos)
      << writeup.ungated[0];
  const CheckOutcome talus = Recheck(file, run, "talus");
  EXPECT_FALSE(talus.Ok());
  EXPECT_TRUE(talus.ungated.empty());
  // gate false ungates every backend, with a reason pointing at the description.
  Truth truth = run.scenario.truths.at(0);
  truth.gate = false;
  MetricResult failing = file.results[0].metrics.at(0);
  Judge(failing, truth.tolerance);
  std::vector<MetricResult> metrics = {failing};
  ApplyGate(truth, "talus", metrics);
  EXPECT_FALSE(metrics[0].checked);
  EXPECT_FALSE(metrics[0].ungated.empty());
}

TEST(Gates, FrictionThreePercentHighFailsTheSlidingGate) {
  ScenarioRun run = LoadRun("sliding/box_slide.json", "box_slide[mu=0.5,v0=3]");
  const CheckOutcome good = Check(run);
  EXPECT_TRUE(good.Ok()) << FirstProblem(good);
  for (BodySpec& body : run.scenario.bodies) body.friction *= 1.03;  // the truth keeps mu = 0.5
  const CheckOutcome broken = Check(run);
  EXPECT_FALSE(broken.Ok());
  EXPECT_NE(FirstProblem(broken).find("sliding_stop.distance"), std::string::npos) << FirstProblem(broken);
}

TEST(Gates, RestitutionTwoAndAHalfPercentLowFailsTheBounceGate) {
  ScenarioRun run = LoadRun("bouncing/sphere_bounce_series.json", "sphere_bounce_series[e=0.5]");
  const CheckOutcome good = Check(run);
  EXPECT_TRUE(good.Ok()) << FirstProblem(good);
  run.scenario.bodies[1].restitution *= 0.975;  // the truth keeps e = 0.5
  const CheckOutcome broken = Check(run);
  EXPECT_FALSE(broken.Ok());
  EXPECT_NE(FirstProblem(broken).find("bounce_heights.apex1"), std::string::npos) << FirstProblem(broken);
}

TEST(Gates, ATippingThresholdOneAndAHalfDegreesOffFailsTheTippingGate) {
  ScenarioRun run = LoadRun("sliding/tall_box_tipping.json", "tall_box_tipping[angle=15deg]");
  const CheckOutcome good = Check(run);
  EXPECT_TRUE(good.Ok()) << FirstProblem(good);
  // A box whose real threshold is 15.54 degrees (truth: 14.04): at 15 degrees it stays.
  auto& box = std::get<BoxShape>(run.scenario.bodies[1].shape);
  box.halfExtents.x() = box.halfExtents.y() * std::tan((14.036 + 1.5) * std::numbers::pi / 180.0);
  const CheckOutcome broken = Check(run);
  EXPECT_FALSE(broken.Ok());
  EXPECT_NE(FirstProblem(broken).find("incline_tip"), std::string::npos) << FirstProblem(broken);
}

TEST(Gates, GravityOnePercentStrongFailsTheTossFlight) {
  ScenarioRun run = LoadRun("tumbling/box_toss.json", "box_toss");
  const CheckOutcome good = Check(run);
  EXPECT_TRUE(good.Ok()) << FirstProblem(good);
  run.scenario.world.gravity *= 1.01;  // the truth keeps g = 9.81
  const CheckOutcome broken = Check(run);
  EXPECT_FALSE(broken.Ok());
  EXPECT_NE(FirstProblem(broken).find("free_fall.height"), std::string::npos) << FirstProblem(broken);
}

}  // namespace
}  // namespace talus::harness
