// Sliding stop: how far the centre of mass travelled across the floor (its
// displacement perpendicular to the up axis, first sample to last) against
// v0^2 / (2 mu g) and the symplectic-Euler sum (truths.h). The run must be
// long enough for the body to stop; a second metric, its final sliding
// speed, must be below the tolerance's absolute distance per second.
#include <cassert>

#include "talus/harness/truths.h"
#include "truth_checks/evaluators.h"

namespace talus::harness {

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
  return {metric};
}

}  // namespace talus::harness
