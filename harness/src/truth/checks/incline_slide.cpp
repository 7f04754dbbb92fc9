// Incline slide: the distance the centre of mass moved from the first
// sample to the last (the block moves only along the slope, so the length
// of its displacement is the distance slid) against a t^2 / 2 with a =
// g (sin angle - mu cos angle), or 0 when tan(angle) <= mu, and against the
// symplectic-Euler sum a h^2 n (n + 1) / 2 (truths.h). Below the threshold
// the tolerance's absolute part is the creep allowed.
#include <cassert>

#include "talus/harness/analytic/truths.h"
#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateInclineSlide(const Run& run, const Truth& truth,
                                               const InclineSlideTruth& kind, const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Sample& first = trajectory.samples.front();
  const Sample& last = trajectory.samples.back();
  MetricResult metric = MakeMetric("incline_slide.distance", "m");
  metric.measured = (last.bodies[body].centerOfMass - first.bodies[body].centerOfMass).norm();
  metric.truth = InclineDistance(kind.angle, kind.mu, kind.g, last.time - first.time);
  metric.truthIntegrator = InclineDistanceSymplecticEuler(kind.angle, kind.mu, kind.g, trajectory.timeStep,
                                                          last.step - first.step);
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
