// The truth evaluators on synthetic trajectories with known answers: they
// read each sample's own step and time (so thinned trajectories give the
// same verdicts), measure along the up axis, and fail what they cannot
// measure.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/run/run_metrics.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace truth_check_test {

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

// A run with a static ground and one dynamic body, `steps` steps of `h`.
Run MakeRun(double h, int steps, ShapeSpec shape = SphereShape{0.1}) {
  Run run;
  run.id = "synthetic";
  run.timeStep = h;
  run.steps = steps;
  run.scenario.world.timeStep = h;
  run.scenario.world.steps = steps;
  BodySpec ground;
  ground.name = "ground";
  ground.motion = Motion::Static;
  ground.shape = BoxShape{Vec3(5, 0.5, 5)};
  BodySpec body;
  body.name = "body";
  body.shape = std::move(shape);
  body.mass = 1.0;
  run.scenario.bodies = {ground, body};
  return run;
}

// A trajectory of body 1 whose centre of mass height at step n is height(n),
// with the velocity of that motion (forward difference), every `stride` steps.
template <typename Height>
Trajectory MakeTrajectory(double h, int steps, int stride, Height height) {
  Trajectory trajectory;
  trajectory.timeStep = h;
  trajectory.stride = stride;
  for (int n = 0; n <= steps; ++n) {
    if (n % stride != 0 && n != steps) continue;
    Sample sample;
    sample.step = n;
    sample.time = n * h;
    sample.bodies.resize(2);
    sample.bodies[1].centerOfMass = Vec3(0, height(n), 0);
    sample.bodies[1].origin = sample.bodies[1].centerOfMass;
    sample.bodies[1].linearVelocity = Vec3(0, (height(n + 1) - height(n)) / h, 0);
    sample.bodies[1].mass = 1.0;
    trajectory.samples.push_back(sample);
  }
  return trajectory;
}

TEST(TruthCheck, FreeFallOnTheSymplecticSequencePassesAtEveryStride) {
  const double h = 1.0 / 60.0;
  const ScenarioRun run = MakeRun(h, 60);
  const Truth truth{FreeFallTruth{10.0, 2.0, 9.81}, 1, Tolerance{1e-9, 0.0}};
  for (int stride : {1, 7, 60}) {
    const Trajectory trajectory = MakeTrajectory(
        h, 60, stride, [&](int n) { return FreeFallHeightSymplecticEuler(10.0, 2.0, 9.81, h, n); });
    const auto metrics = EvaluateTruth(run, truth, trajectory);
    ASSERT_EQ(metrics.size(), 1u);
    EXPECT_TRUE(metrics[0].checked);
    EXPECT_TRUE(metrics[0].pass) << "stride " << stride << " error " << metrics[0].error;
    EXPECT_LT(std::abs(metrics[0].error), 1e-12);
  }
}

TEST(TruthCheck, FreeFallAcceptsEachIntegratorsClosedFormAndNothingBetween) {
  // The parabola (a scheme exact for constant gravity) and explicit Euler's
  // sequence pass as the symplectic sequence does; a run between two forms
  // (half of g h t / 2 = 4 cm off each after 1 s) fails, at its worst sample.
  const double h = 1.0 / 60.0;
  const ScenarioRun run = MakeRun(h, 60);
  const Truth truth{FreeFallTruth{10.0, 2.0, 9.81}, 1, Tolerance{1e-9, 0.0}};
  const auto parabola = [&](int n) { return FreeFallHeight(10.0, 2.0, 9.81, n * h); };
  const auto explicitEuler = [&](int n) { return FreeFallHeightExplicitEuler(10.0, 2.0, 9.81, h, n); };
  for (const auto& form : {std::function<double(int)>(parabola), std::function<double(int)>(explicitEuler)}) {
    const auto metrics = EvaluateTruth(run, truth, MakeTrajectory(h, 60, 1, form));
    ASSERT_EQ(metrics.size(), 1u);
    EXPECT_TRUE(metrics[0].pass) << metrics[0].error;
  }
  const auto between = [&](int n) {
    return 0.5 *
           (FreeFallHeight(10.0, 2.0, 9.81, n * h) + FreeFallHeightSymplecticEuler(10.0, 2.0, 9.81, h, n));
  };
  const auto metrics = EvaluateTruth(run, truth, MakeTrajectory(h, 60, 1, between));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(std::abs(metrics[0].error), 9.81 * h * 1.0 / 4.0, 1e-9);
}

TEST(TruthCheck, FreeFallUnderWrongGravityFailsEveryForm) {
  // 1% too much gravity: 4.9 cm below the symplectic sequence after 1 s, and
  // further from the other two forms.
  const double h = 1.0 / 60.0;
  const ScenarioRun run = MakeRun(h, 60);
  const Truth truth{FreeFallTruth{10.0, 2.0, 9.81}, 1, Tolerance{1e-3, 0.0}};
  const auto metrics = EvaluateTruth(run, truth, MakeTrajectory(h, 60, 1, [&](int n) {
                                       return FreeFallHeightSymplecticEuler(10.0, 2.0, 9.81 * 1.01, h, n);
                                     }));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_FALSE(metrics[0].pass);
}

TEST(TruthCheck, UpAxisFollowsGravity) {
  ScenarioRun run = MakeRun(0.01, 10);
  run.scenario.world.gravity = Vec3(0, 0, -3);
  EXPECT_TRUE(UpAxis(run).isApprox(Vec3::UnitZ()));
  run.scenario.world.gravity = Vec3::Zero();
  EXPECT_TRUE(UpAxis(run).isApprox(Vec3::UnitY()));
}

TEST(TruthCheck, BounceApexesAreFoundAtTheirStepsAndMissingOnesFail) {
  // Lowest point of a 0.1 m sphere: 1 m drop, then apexes 0.49 and 0.2401
  // (parabolic arcs between impacts at y = 0), sampled every step.
  const double h = 0.001;
  const double g = 9.81;
  const auto lowest = [&](int n) {
    const double t = n * h;
    const double v0 = std::sqrt(2 * g * 1.0);
    const double t0 = v0 / g;  // first impact
    if (t < t0) return 1.0 - 0.5 * g * t * t;
    double start = t0;
    double speed = 0.7 * v0;
    while (true) {
      const double flight = 2 * speed / g;
      if (t < start + flight) {
        const double s = t - start;
        return speed * s - 0.5 * g * s * s;
      }
      start += flight;
      speed *= 0.7;
    }
  };
  const ScenarioRun run = MakeRun(h, 2500);
  const Truth truth{BounceHeightsTruth{1.0, 0.7, 2}, 1, Tolerance{0.0, 0.01}};
  for (int stride : {1, 5}) {
    const Trajectory trajectory = MakeTrajectory(h, 2500, stride, [&](int n) { return lowest(n) + 0.1; });
    const auto metrics = EvaluateTruth(run, truth, trajectory);
    ASSERT_EQ(metrics.size(), 4u);  // each apex, then its step allowance
    EXPECT_EQ(metrics[0].name, "bounce_heights.apex1");
    // Apex known to within one stride of travel near the top: g (stride h)^2.
    EXPECT_NEAR(metrics[0].measured, 0.49, g * (stride * h) * (stride * h) + 1e-6) << "stride " << stride;
    EXPECT_NEAR(metrics[2].measured, 0.2401, g * (stride * h) * (stride * h) + 1e-6) << "stride " << stride;
    EXPECT_TRUE(metrics[0].pass && metrics[2].pass);
  }
  // Cut before the second apex: it is not measured, and fails.
  const ScenarioRun shortRun = MakeRun(h, 800);
  const Trajectory cut = MakeTrajectory(h, 800, 1, [&](int n) { return lowest(n) + 0.1; });
  const auto metrics = EvaluateTruth(shortRun, truth, cut);
  ASSERT_EQ(metrics.size(), 4u);
  EXPECT_TRUE(std::isnan(metrics[2].measured));
  EXPECT_FALSE(metrics[2].pass);
}

TEST(TruthCheck, TheStepAllowanceOfABounceIsReportedBesideTheApexNotAddedToIt) {
  // An apex 3 mm high: inside the first apex's step allowance at 1 kHz
  // ((1 + e^2) sqrt(2 g h) h = 6.6 mm) but outside the 0.5 mm tolerance.
  const double h = 0.001;
  const double g = 9.81;
  const double v0 = std::sqrt(2 * g * 1.0);
  const double up = 0.7 * v0 * std::sqrt(1.0 + 2 * g * 0.003 / (0.49 * v0 * v0));  // to 0.493 m
  const auto lowest = [&](int n) {
    const double t = n * h;
    const double t0 = v0 / g;
    if (t < t0) return 1.0 - 0.5 * g * t * t;
    const double s = t - t0;
    return up * s - 0.5 * g * s * s;
  };
  const ScenarioRun run = MakeRun(h, 1200);
  const Truth truth{BounceHeightsTruth{1.0, 0.7, 1}, 1, Tolerance{0.0005, 0.0}};
  const auto metrics =
      EvaluateTruth(run, truth, MakeTrajectory(h, 1200, 1, [&](int n) { return lowest(n) + 0.1; }));
  ASSERT_EQ(metrics.size(), 2u);
  EXPECT_NEAR(metrics[0].measured, 0.493, 1e-5);
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_EQ(metrics[0].tolerance.absolute, 0.0005);
  EXPECT_EQ(metrics[1].name, "bounce_heights.apex1.step_allowance");
  EXPECT_NEAR(metrics[1].measured, (1.0 + 0.49) * v0 * h, 1e-12);
  // Reported only: no tolerance, so never judged and outside the sweep's error.
  EXPECT_FALSE(metrics[1].checked);
  EXPECT_EQ(metrics[1].tolerance.absolute, 0.0);
  EXPECT_EQ(metrics[1].tolerance.relative, 0.0);
}

TEST(TruthCheck, RestHeightJitterIsPeakToPeakOverTheSecondHalf) {
  const double h = 0.01;
  const ScenarioRun run = MakeRun(h, 100);
  const Truth truth{RestHeightTruth{0.5, 1e-3}, 1, Tolerance{0.01, 0.0}};
  // Falls in from 0.6 during the first half (ignored), then oscillates +-0.4 mm.
  const Trajectory trajectory = MakeTrajectory(
      h, 100, 1, [](int n) { return n < 50 ? 0.6 - 0.002 * n : 0.5 + (n % 2 == 0 ? 4e-4 : -4e-4); });
  auto metrics = EvaluateTruth(run, truth, trajectory);
  ASSERT_EQ(metrics.size(), 2u);
  EXPECT_EQ(metrics[1].name, "rest_height.jitter");
  EXPECT_NEAR(metrics[1].measured, 8e-4, 1e-12);
  EXPECT_TRUE(metrics[0].pass);
  EXPECT_TRUE(metrics[1].pass);
  // A larger jitter fails against maxJitter even though the height passes.
  const Truth tight{RestHeightTruth{0.5, 5e-4}, 1, Tolerance{0.01, 0.0}};
  metrics = EvaluateTruth(run, tight, trajectory);
  EXPECT_TRUE(metrics[0].pass);
  EXPECT_FALSE(metrics[1].pass);
}

TEST(TruthCheck, SlidingStopMeasuresHorizontalTravelOnly) {
  const double h = 0.01;
  ScenarioRun run = MakeRun(h, 10);
  Trajectory trajectory = MakeTrajectory(h, 10, 1, [](int) { return 0.25; });
  trajectory.samples.back().bodies[1].centerOfMass = Vec3(0.3, 0.2, 0.4);  // 0.5 m across, 5 cm down
  const Truth truth{SlidingStopTruth{1.0, 0.1, 10.0}, 1, Tolerance{0.0, 0.01}};
  const auto metrics = EvaluateTruth(run, truth, trajectory);
  ASSERT_EQ(metrics.size(), 3u);  // distance, stop time, lateral deviation
  EXPECT_NEAR(metrics[0].measured, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(metrics[0].truth, 0.5);  // 1 / (2 * 0.1 * 10)
  EXPECT_DOUBLE_EQ(metrics[0].truthIntegrator, SlidingStopDistanceSymplecticEuler(1.0, 0.1, 10.0, h));
}

TEST(TruthCheck, ToleranceIsAbsolutePlusRelativeAndZeroMeansUnchecked) {
  MetricResult metric = MakeMetric("m", "m");
  metric.measured = 1.049;
  metric.truth = 1.0;
  Judge(metric, Tolerance{0.02, 0.03});
  EXPECT_TRUE(metric.checked);
  EXPECT_TRUE(metric.pass);  // 0.049 <= 0.02 + 0.03 * 1
  metric.measured = 1.051;
  Judge(metric, Tolerance{0.02, 0.03});
  EXPECT_FALSE(metric.pass);
  Judge(metric, Tolerance{});
  EXPECT_FALSE(metric.checked);
}

TEST(RunMetrics, ConvergedReferenceComparesAtCommonTimesOnly) {
  const Truth truth{ConvergedReferenceTruth{4}, -1, Tolerance{1e-3, 0.0}};
  const Trajectory coarse = MakeTrajectory(0.04, 10, 1, [](int n) { return 1.0 + 0.001 * n; });
  // The fine run has 4x the samples, equal at common times except 2 mm at t = 0.2 s.
  const Trajectory fine = MakeTrajectory(0.01, 40, 1, [](int n) {
    return 1.0 + 0.00025 * n + (n == 20 ? 0.002 : 0.0) + (n % 4 != 0 ? 5.0 : 0.0);
  });
  const auto metrics = CompareWithReference(truth, coarse, fine);
  ASSERT_EQ(metrics.size(), 2u);
  EXPECT_NEAR(metrics[0].measured, 0.002, 1e-12);
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(metrics[1].measured, 0.0, 1e-12);
}

TEST(RunMetrics, ClosedSystemDriftsAreZeroForExactFreeFall) {
  // Momentum under gravity alone: P = P0 + M g t exactly, so no drift.
  ScenarioRun run = MakeRun(0.01, 10);
  run.scenario.bodies.erase(run.scenario.bodies.begin());
  EXPECT_TRUE(IsClosedSystem(run));
  EXPECT_FALSE(IsClosedSystem(MakeRun(0.01, 10)));
  // A load, an impulse or a kinematic body acts from outside as a static body does.
  ScenarioRun pushed = run;
  pushed.scenario.loads.push_back(AppliedLoad{.body = 0, .force = Vec3(1, 0, 0)});
  EXPECT_FALSE(IsClosedSystem(pushed));
  ScenarioRun struck = run;
  struck.scenario.impulses.push_back(AppliedImpulse{.body = 0, .linear = Vec3(1, 0, 0)});
  EXPECT_FALSE(IsClosedSystem(struck));
  ScenarioRun carried = MakeRun(0.01, 10);
  carried.scenario.bodies.front().motion = Motion::Kinematic;
  EXPECT_FALSE(IsClosedSystem(carried));
  Trajectory trajectory;
  trajectory.timeStep = 0.01;
  for (int n = 0; n <= 10; ++n) {
    Sample sample;
    sample.step = n;
    sample.time = n * 0.01;
    sample.bodies.resize(1);
    sample.bodies[0].mass = 2.0;
    sample.measures.linearMomentum = Vec3(1.0, 2.0 * -9.81 * sample.time, 0.0);
    trajectory.samples.push_back(sample);
  }
  const auto momentum = MomentumDrift(run, trajectory);
  ASSERT_EQ(momentum.size(), 2u);
  EXPECT_LT(momentum[0].measured, 1e-12);
  trajectory.samples[5].measures.linearMomentum.x() += 0.5;
  EXPECT_NEAR(MomentumDrift(run, trajectory)[0].measured, 0.5, 1e-12);
}

}  // namespace truth_check_test
}  // namespace talus::harness
