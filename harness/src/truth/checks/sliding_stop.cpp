// Sliding stop: how far the centre of mass travelled across the floor (its
// displacement perpendicular to the up axis, first sample to last) against
// v0^2 / (2 mu g) and the symplectic-Euler sum (truths.h). The run must be
// long enough for the body to stop. Two more metrics: the stop time, the
// first sample whose speed across the floor is below kStoppedSpeed, against
// v0 / (mu g) and ceil(v0 / (mu g h)) h, judged with the same tolerance
// plus one sample interval (the speed threshold is crossed up to one sample
// before the exact stop); and the lateral deviation, the
// largest distance of the centre of mass from the launch line (start point,
// truth direction) across the floor, checked against maxLateral: a
// pyramid friction cone (ODE) bends paths launched off its axes.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "talus/harness/analytic/truths.h"
#include "truth/checks/evaluators.h"

namespace talus::harness {
namespace {

// Speed (m/s) below which a sliding body counts as stopped: iterative
// solvers leave residual speeds of mm/s, and from 1 cm/s friction stops a
// body within 0.01 / (mu g) < 4 ms (mu >= 0.3), less than one 60 Hz step.
constexpr double kStoppedSpeed = 0.01;

}  // namespace

std::vector<MetricResult> EvaluateSlidingStop(const Run& run, const Truth& truth,
                                              const SlidingStopTruth& kind, const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Vec3 up = UpAxis(run);
  const Vec3 start = trajectory.samples.front().bodies[body].centerOfMass;
  const Vec3 end = trajectory.samples.back().bodies[body].centerOfMass;
  const Vec3 travel = end - start;
  MetricResult metric = MakeMetric("sliding_stop.distance", "m");
  metric.measured = (travel - travel.dot(up) * up).norm();
  metric.truth = SlidingStopDistance(kind.v0, kind.mu, kind.g);
  metric.truthIntegrator = SlidingStopDistanceSymplecticEuler(kind.v0, kind.mu, kind.g, trajectory.timeStep);
  Judge(metric, truth.tolerance);

  MetricResult time = MakeMetric("sliding_stop.time", "s");
  time.measured = std::numeric_limits<double>::quiet_NaN();
  double lateral = 0.0;
  const Vec3 direction = (kind.direction - kind.direction.dot(up) * up).normalized();
  for (const Sample& sample : trajectory.samples) {
    const BodyReading& state = sample.bodies[body];
    const Vec3 velocity = state.linearVelocity - state.linearVelocity.dot(up) * up;
    if (std::isnan(time.measured) && velocity.norm() < kStoppedSpeed) time.measured = sample.time;
    const Vec3 offset = state.centerOfMass - start;
    const Vec3 across = offset - offset.dot(up) * up - offset.dot(direction) * direction;
    lateral = std::max(lateral, across.norm());
  }
  time.truth = SlidingStopTime(kind.v0, kind.mu, kind.g);
  time.truthIntegrator = SlidingStopTimeSymplecticEuler(kind.v0, kind.mu, kind.g, trajectory.timeStep);
  // The stop is seen at the first sample below kStoppedSpeed, which can be
  // one sample before the step where the speed reaches 0: one sample
  // interval is added to the file's tolerance.
  Tolerance timeTolerance = truth.tolerance;
  timeTolerance.absolute += trajectory.timeStep * trajectory.stride;
  Judge(time, timeTolerance);
  MetricResult deviation = MakeMetric("sliding_stop.lateral", "m");
  deviation.measured = lateral;
  deviation.truth = 0.0;
  Judge(deviation, Tolerance{.absolute = kind.maxLateral, .relative = 0.0});
  return {metric, time, deviation};
}

}  // namespace talus::harness
