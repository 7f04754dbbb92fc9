// The scenario's "gyroscopic" world setting reaches every backend: with it
// on, a torque-free asymmetric box keeps its world angular momentum and
// turns over about its intermediate axis (Dzhanibekov); with it off, w
// stays fixed in the world, L turns with the body, and nothing flips. The
// scenes are the shipped tumbling files, so the tests and the testbed read
// the same bodies and durations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "talus/harness/backend/backend.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace gyroscopic_backends_test {

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

const BackendRegistry& Registry() { return reference::AllBackends(); }

// The file's single run with the gyroscopic setting forced to `gyroscopic`.
Run LoadTumbling(const std::string& file, bool gyroscopic) {
  auto runs = LoadScenarioFile(std::string(TALUS_SCENARIO_DIR) + "/tumbling/" + file);
  EXPECT_TRUE(runs) << runs.GetError().message;
  if (!runs || runs.Value().size() != 1) return Run{};
  Run run = runs.Value()[0];
  run.scenario.world.gyroscopic = gyroscopic;
  return run;
}

// What one torque-free run did: the largest relative drift of the world
// angular momentum vector and of its magnitude, and the sign changes of the
// body-frame intermediate (y) component of w, each one a turn-over.
struct SpinRecord {
  double momentumDrift = 0.0;
  double magnitudeDrift = 0.0;
  int flips = 0;
};

SpinRecord Spin(const std::string& backendName, const Run& run) {
  auto created = Registry().Create(backendName, run);
  EXPECT_TRUE(created) << created.GetError().message;
  SpinRecord record;
  if (!created) return record;
  Backend& backend = *created.Value();
  const auto momentum = [&backend] {
    const BodyReading s = backend.GetBodyState(0);
    return Vec3(s.worldInertia * s.angularVelocity);
  };
  const auto intermediate = [&backend] {
    const BodyReading s = backend.GetBodyState(0);
    return (s.orientation.conjugate() * s.angularVelocity).y();
  };
  const Vec3 initial = momentum();
  double previous = intermediate();
  for (int n = 0; n < run.steps; ++n) {
    backend.Step();
    const Vec3 now = momentum();
    record.momentumDrift = std::max(record.momentumDrift, (now - initial).norm() / initial.norm());
    record.magnitudeDrift =
        std::max(record.magnitudeDrift, std::abs(now.norm() - initial.norm()) / initial.norm());
    const double current = intermediate();
    if ((current > 0.0) != (previous > 0.0)) ++record.flips;
    previous = current;
  }
  return record;
}

class GyroscopicSetting : public ::testing::TestWithParam<std::string> {};

TEST_P(GyroscopicSetting, IsRecordedInTheSettings) {
  for (const bool on : {true, false}) {
    auto backend = Registry().Create(GetParam(), LoadTumbling("box_torque_free.json", on));
    ASSERT_TRUE(backend) << backend.GetError().message;
    std::map<std::string, std::string> settings;
    for (const auto& setting : backend.Value()->Settings()) settings[setting.key] = setting.value;
    EXPECT_EQ(settings["gyroscopic term"].substr(0, 3), on ? "on " : "off") << settings["gyroscopic term"];
  }
}

TEST_P(GyroscopicSetting, OnConservesAngularMomentumOfAnAsymmetricBox) {
  // 1 x 0.5 x 0.25 m box at (0.5, 0.5, 3) rad/s for 10 s at 60 Hz. |L|
  // within 1%, the scenario's tolerance: an implicit gyroscopic step loses a
  // little energy per step (largest measured: Bullet 0.70%). The vector
  // within 2%: Bullet's also turns by 1.2%. Without the term L turns with
  // the body by 25% (next test).
  const ScenarioRun run = LoadTumbling("box_torque_free.json", true);
  ASSERT_GT(run.steps, 0);
  const SpinRecord record = Spin(GetParam(), run);
  EXPECT_LT(record.magnitudeDrift, 0.01);
  EXPECT_LT(record.momentumDrift, 0.02);
}

TEST_P(GyroscopicSetting, OffLetsAngularMomentumTurnWithTheBody) {
  // w fixed in the world while I_world turns: L swings by tens of percent.
  const SpinRecord record = Spin(GetParam(), LoadTumbling("box_torque_free.json", false));
  EXPECT_GT(record.momentumDrift, 0.1);
}

// The largest relative |L| drift each engine shows over the 25 s of
// box_intermediate_axis with the term on, measured, plus margin: the
// turn-overs pass through a fast tumble where an implicit step errs most.
// Talus and Bullet (the same body-frame Newton step) lose up to 10.5%
// mid-flip yet keep the 6.93 s interval; ODE's loses 3.8%, and it then
// flips every 1.65 to 1.95 s. The flip count carries the test; the bound catches a
// step that gains or sheds momentum wholesale.
double IntermediateAxisMomentumBound(const std::string& backend) {
  return backend.starts_with("ode") ? 0.05 : 0.12;
}

TEST_P(GyroscopicSetting, OnFlipsAboutTheIntermediateAxis) {
  // Euler's equations turn the box over every 6.93 s (flip_period truth),
  // so 25 s hold at least three turn-overs.
  const ScenarioRun run = LoadTumbling("box_intermediate_axis.json", true);
  ASSERT_GT(run.steps, 0);
  const SpinRecord record = Spin(GetParam(), run);
  EXPECT_GE(record.flips, 3);
  EXPECT_LT(record.magnitudeDrift, IntermediateAxisMomentumBound(GetParam()));
}

TEST_P(GyroscopicSetting, OffNeverFlips) {
  const SpinRecord record = Spin(GetParam(), LoadTumbling("box_intermediate_axis.json", false));
  EXPECT_EQ(record.flips, 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, GyroscopicSetting,
                         ::testing::Values("talus", "talus-writeup", "talus-split", "bullet", "ode-step",
                                           "ode-quickstep"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace gyroscopic_backends_test
}  // namespace talus::harness
