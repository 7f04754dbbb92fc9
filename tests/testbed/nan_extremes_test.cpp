// A value that could not be measured must fail the metric built on it,
// never vanish from a running maximum (support/nan_extremes.h): the
// helpers keep NaN, and the evaluators that take running extremes over a
// trajectory turn one NaN sample into a failing metric.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "talus/harness/support/nan_extremes.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace nan_extremes_test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

TEST(NanExtremes, KeepNaNWhereStdMaxAndMinDropIt) {
  // What the helpers replace: std::max drops a NaN second argument.
  EXPECT_EQ(std::max(1.0, kNaN), 1.0);
  EXPECT_EQ(std::min(1.0, kNaN), 1.0);
  EXPECT_TRUE(std::isnan(MaxKeepingNaN(1.0, kNaN)));
  EXPECT_TRUE(std::isnan(MaxKeepingNaN(kNaN, 1.0)));
  EXPECT_TRUE(std::isnan(MinKeepingNaN(1.0, kNaN)));
  EXPECT_TRUE(std::isnan(MinKeepingNaN(kNaN, 1.0)));
  EXPECT_EQ(MaxKeepingNaN(1.0, 2.0), 2.0);
  EXPECT_EQ(MinKeepingNaN(1.0, 2.0), 1.0);
}

// A box resting at 0.5 m for 100 steps, one sample in the second half NaN.
TEST(NanExtremes, ANaNSampleFailsTheRestJitterAndTheStackDrift) {
  ScenarioRun run;
  run.id = "rest";
  run.timeStep = 0.01;
  run.steps = 100;
  BodySpec ground;
  ground.name = "ground";
  ground.motion = Motion::Static;
  ground.shape = BoxShape{Vec3(5, 0.5, 5)};
  BodySpec box;
  box.name = "box";
  box.shape = BoxShape{Vec3(0.5, 0.5, 0.5)};
  box.mass = 1.0;
  run.scenario.bodies = {ground, box};
  run.scenario.world.gravity = Vec3(0, -9.81, 0);
  Trajectory trajectory;
  trajectory.timeStep = run.timeStep;
  for (int n = 0; n <= run.steps; ++n) {
    Sample sample;
    sample.step = n;
    sample.time = n * run.timeStep;
    sample.bodies.resize(2);
    sample.bodies[1].centerOfMass = Vec3(0, n == 80 ? kNaN : 0.5, 0);
    sample.bodies[1].origin = sample.bodies[1].centerOfMass;
    trajectory.samples.push_back(sample);
  }
  Truth rest{RestHeightTruth{0.5, 1e-3}, 1, Tolerance{0.01, 0.0}};
  bool sawJitter = false;
  for (const MetricResult& metric : EvaluateTruth(run, rest, trajectory)) {
    if (metric.name != "rest_height.jitter") continue;
    sawJitter = true;
    EXPECT_TRUE(std::isnan(metric.measured));
    EXPECT_FALSE(metric.pass);
  }
  EXPECT_TRUE(sawJitter);
  Truth stack{StackRestTruth{{{1}}, 0.0, 1.0, 0.01}, -1, Tolerance{0.01, 0.0}};
  // The last sample NaN: the drift from the middle sample to it.
  trajectory.samples.back().bodies[1].centerOfMass.y() = kNaN;
  bool sawDrift = false;
  for (const MetricResult& metric : EvaluateTruth(run, stack, trajectory)) {
    if (metric.name != "stack_rest.drift") continue;
    sawDrift = true;
    EXPECT_TRUE(std::isnan(metric.measured));
    EXPECT_FALSE(metric.pass);
  }
  EXPECT_TRUE(sawDrift);
}

}  // namespace nan_extremes_test
}  // namespace talus::harness
