// The testbed's Talus rows (docs/testbed-backends.md, "The Talus rows"): the
// `talus` row is WorldSettings{} unchanged but for the choices a scenario
// states, on every shipped scenario and on a run that states every choice
// there is; each other row departs from it by its listed settings only, and
// its settings text names each departure with the engine's default and the
// reason. Whole settings are compared (WorldSettings::operator==), so a
// field added to the engine later is covered without touching this file.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/all_backends.h"
#include "talus/reference/talus_backend.h"

namespace talus::reference {
namespace talus_rows_test {

// Every run of the shipped suite, scenarios/ as talus-testbed run reads it
// (sweeps expanded).
std::vector<harness::Run> EveryShippedRun() {
  auto runs = harness::LoadScenarios({TALUS_SCENARIO_DIR});
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value() : std::vector<harness::Run>{};
}

harness::Run BoxRest() {
  auto runs = harness::LoadScenarioFile(std::string(TALUS_SCENARIO_DIR) + "/stacking/box_rest.json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value().at(0) : harness::Run{};
}

FrictionCombine FrictionRule(harness::CombineRule rule) {
  const std::map<harness::CombineRule, FrictionCombine> rules = {
      {harness::CombineRule::Sqrt, FrictionCombine::GeometricMean},
      {harness::CombineRule::Min, FrictionCombine::Min},
      {harness::CombineRule::Max, FrictionCombine::Max},
      {harness::CombineRule::Multiply, FrictionCombine::Product},
      {harness::CombineRule::Average, FrictionCombine::Average}};
  return rules.at(rule);
}

RestitutionCombine RestitutionRule(harness::CombineRule rule) {
  const std::map<harness::CombineRule, RestitutionCombine> rules = {
      {harness::CombineRule::Min, RestitutionCombine::Min},
      {harness::CombineRule::Max, RestitutionCombine::Max},
      {harness::CombineRule::Multiply, RestitutionCombine::Product},
      {harness::CombineRule::Average, RestitutionCombine::Average}};
  return rules.at(rule);
}

// Checks each choice the scenario states against what the row set, then
// puts it back to WorldSettings{}'s value: what is left must be the
// defaults exactly.
WorldSettings WithoutScenarioChoices(WorldSettings s, const harness::Run& run) {
  const WorldSettings defaults;
  const harness::WorldSpec& world = run.scenario.world;
  EXPECT_EQ(s.gravity, world.gravity);
  s.gravity = defaults.gravity;
  const int iterations = run.iterations > 0 ? run.iterations : defaults.velocityIterations;
  EXPECT_EQ(s.velocityIterations, iterations);
  EXPECT_EQ(s.positionIterations, run.iterations > 0 ? run.iterations : defaults.positionIterations);
  s.velocityIterations = defaults.velocityIterations;
  s.positionIterations = defaults.positionIterations;
  EXPECT_EQ(s.frictionCombine, FrictionRule(world.frictionCombine));
  EXPECT_EQ(s.restitutionCombine, RestitutionRule(world.restitutionCombine));
  s.frictionCombine = defaults.frictionCombine;
  s.restitutionCombine = defaults.restitutionCombine;
  EXPECT_FALSE(s.sleeping);  // the peers never sleep
  s.sleeping = defaults.sleeping;
  EXPECT_EQ(s.methods.rotation,
            world.gyroscopic ? defaults.methods.rotation : RotationIntegrator::ConstantRate);
  s.methods.rotation = defaults.methods.rotation;
  switch (world.broadPhase) {
    case harness::BroadPhaseChoice::Auto:
      break;
    case harness::BroadPhaseChoice::UniformGrid:
    case harness::BroadPhaseChoice::AabbTree:
    case harness::BroadPhaseChoice::BruteForce: {
      const std::map<harness::BroadPhaseChoice, BroadPhaseKind> kinds = {
          {harness::BroadPhaseChoice::UniformGrid, BroadPhaseKind::UniformGrid},
          {harness::BroadPhaseChoice::AabbTree, BroadPhaseKind::AabbTree},
          {harness::BroadPhaseChoice::BruteForce, BroadPhaseKind::BruteForce}};
      EXPECT_EQ(s.broadPhase, kinds.at(world.broadPhase));
      EXPECT_TRUE(s.methods.forceBroadPhase);
      s.broadPhase = defaults.broadPhase;
      s.methods.forceBroadPhase = defaults.methods.forceBroadPhase;
      break;
    }
  }
  if (world.bounceTiming != harness::BounceTimingChoice::Auto) {
    EXPECT_EQ(s.methods.bounceTiming, world.bounceTiming == harness::BounceTimingChoice::StepBoundary
                                          ? BounceTiming::StepBoundary
                                          : BounceTiming::TimeOfImpact);
    s.methods.bounceTiming = defaults.methods.bounceTiming;
  }
  return s;
}

// A run of box_rest that states every choice there is, each away from the
// engine's default.
harness::Run RunStatingEveryChoice() {
  harness::Run run = BoxRest();
  run.iterations = 7;
  run.scenario.world.gravity = Vec3(0.5, -3.0, 0.25);
  run.scenario.world.frictionCombine = harness::CombineRule::Min;
  run.scenario.world.restitutionCombine = harness::CombineRule::Average;
  run.scenario.world.gyroscopic = false;
  run.scenario.world.broadPhase = harness::BroadPhaseChoice::AabbTree;
  run.scenario.world.bounceTiming = harness::BounceTimingChoice::StepBoundary;
  return run;
}

TEST(TalusRows, TheTalusRowIsTheEngineDefaultsOnEveryShippedScenario) {
  const std::vector<harness::Run> runs = EveryShippedRun();
  ASSERT_GE(runs.size(), 19u);  // at least one run per shipped scenario file
  for (const harness::Run& run : runs) {
    SCOPED_TRACE(run.scenario.name);
    auto settings = TalusRowSettings(run, "talus");
    ASSERT_TRUE(settings) << settings.GetError().message;
    EXPECT_TRUE(WithoutScenarioChoices(settings.Value(), run) == WorldSettings{});
  }
}

TEST(TalusRows, TheTalusRowDepartsOnlyByWhatTheScenarioStates) {
  const harness::Run run = RunStatingEveryChoice();
  auto settings = TalusRowSettings(run, "talus", {.threads = 3});
  ASSERT_TRUE(settings) << settings.GetError().message;
  EXPECT_EQ(settings.Value().threads, 3);  // the run's option, not a physics setting
  WorldSettings left = WithoutScenarioChoices(settings.Value(), run);
  left.threads = WorldSettings{}.threads;
  EXPECT_TRUE(left == WorldSettings{});
  // The comparison can fail: one field off the defaults is seen.
  left.methods.speculativeMotion = !left.methods.speculativeMotion;
  EXPECT_FALSE(left == WorldSettings{});
}

TEST(TalusRows, EachVariantDepartsFromTheTalusRowByItsListedSettingsOnly) {
  for (const harness::Run& run : {BoxRest(), RunStatingEveryChoice()}) {
    SCOPED_TRACE(run.scenario.world.gyroscopic ? "gyroscopic" : "no gyroscopic term");
    const WorldSettings talus = TalusRowSettings(run, "talus").Value();

    WorldSettings split = talus;
    split.methods.positionCorrection = PositionCorrection::SplitImpulses;
    EXPECT_TRUE(TalusRowSettings(run, "talus-split").Value() == split);

    WorldSettings coloured = talus;
    coloured.methods.contactOrder = ContactOrder::ByColour;
    coloured.methods.frictionSolve = FrictionSolve::PerPoint;
    EXPECT_TRUE(TalusRowSettings(run, "talus-coloured").Value() == coloured);

    WorldSettings soft = talus;
    soft.methods.stepSolver = StepSolver::SoftStep;
    soft.methods.frictionSolve = FrictionSolve::PerPoint;
    EXPECT_TRUE(TalusRowSettings(run, "talus-soft").Value() == soft);
    WorldSettings manifold = talus;
    manifold.methods.frictionSolve = FrictionSolve::PerManifold;
    EXPECT_TRUE(TalusRowSettings(run, "talus-manifold").Value() == manifold);
    WorldSettings coupled = talus;
    coupled.methods.frictionSolve = FrictionSolve::CoupledBlock;
    EXPECT_TRUE(TalusRowSettings(run, "talus-coupled").Value() == coupled);

    WorldSettings writeUp = talus;
    if (run.scenario.world.gyroscopic) writeUp.methods.rotation = RotationIntegrator::MomentumSplitting;
    if (run.scenario.world.bounceTiming == harness::BounceTimingChoice::Auto) {
      writeUp.methods.bounceTiming = BounceTiming::StepBoundary;
    }
    writeUp.methods.translation = TranslationIntegrator::SymplecticEuler;
    writeUp.methods.narrowPhase.satMode = SatMode::Full;
    writeUp.methods.narrowPhase.manifoldMode = ManifoldMode::WriteUp;
    writeUp.methods.narrowPhase.useSatCache = false;
    writeUp.methods.narrowPhase.reuseDistance = 0.0;
    writeUp.methods.narrowPhase.persistence = ManifoldPersistence::Fresh;
    writeUp.methods.speculativeMotion = false;
    writeUp.methods.warmStarting = false;
    writeUp.methods.blockSolver = false;
    writeUp.methods.maxVelocityIterations = 1;
    writeUp.methods.frictionSolve = FrictionSolve::PerPoint;
    writeUp.methods.shockPropagation = false;
    EXPECT_TRUE(TalusRowSettings(run, "talus-writeup").Value() == writeUp);
  }
  const auto unknown = TalusRowSettings(BoxRest(), "talus-fast");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.GetError().message.find("\"talus-fast\" is not a Talus row"), std::string::npos)
      << unknown.GetError().message;
}

// The departures each row's settings text records (engineDefault set), each
// with its reason; the talus row records none.
std::set<std::string> Departures(const std::string& row, const harness::Run& run) {
  auto backend = AllBackends().Create(row, run);
  EXPECT_TRUE(backend) << backend.GetError().message;
  std::set<std::string> keys;
  if (!backend) return keys;
  for (const harness::Setting& setting : backend.Value()->Settings()) {
    if (setting.engineDefault.empty()) continue;
    EXPECT_FALSE(setting.effect.empty()) << row << ": " << setting.key;
    EXPECT_NE(setting.value, setting.engineDefault) << row << ": " << setting.key;
    keys.insert(setting.key);
  }
  return keys;
}

TEST(TalusRows, EachRowsSettingsTextListsItsDepartures) {
  const harness::Run run = BoxRest();  // gyroscopic term on, bounce timing auto
  ASSERT_TRUE(run.scenario.world.gyroscopic);
  EXPECT_EQ(Departures("talus", run), std::set<std::string>{});
  EXPECT_EQ(Departures("talus", RunStatingEveryChoice()), std::set<std::string>{});
  EXPECT_EQ(Departures("talus-split", run), std::set<std::string>{"position correction"});
  EXPECT_EQ(Departures("talus-coloured", run), (std::set<std::string>{"solver", "friction solve"}));
  EXPECT_EQ(Departures("talus-soft", run), (std::set<std::string>{"solver", "friction solve"}));
  EXPECT_EQ(Departures("talus-manifold", run), std::set<std::string>{"friction solve"});
  EXPECT_EQ(Departures("talus-coupled", run), std::set<std::string>{"friction solve"});
  EXPECT_EQ(
      Departures("talus-writeup", run),
      (std::set<std::string>{"integrator", "warm starting", "block solver (a pair's normal rows together)",
                             "friction solve", "extra velocity sweeps for new contacts", "bounce timing",
                             "SAT", "SAT cache", "manifold reuse (m of relative motion)", "manifolds",
                             "persistent points (m break distance)", "speculative margin (m)",
                             "gyroscopic term", "shock propagation"}));
}

}  // namespace talus_rows_test
}  // namespace talus::reference
