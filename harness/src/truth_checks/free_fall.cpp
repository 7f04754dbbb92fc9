// Free fall: the centre of mass height along the up axis against the
// parabola y0 + v0 t - g t^2 / 2 and against the symplectic-Euler sequence
// (truths.h), whichever the run follows (an engine exact for constant
// acceleration follows the parabola). The metric is taken at the recorded
// sample where the height strays furthest from the integrator's answer, so
// a deviation anywhere in the run is reported, not only at its end. Samples after `until` (a
// landing) are not judged.
#include <cassert>
#include <cmath>

#include "talus/harness/truths.h"
#include "truth_checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateFreeFall(const Run& run, const Truth& truth, const FreeFallTruth& kind,
                                           const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const Vec3 up = UpAxis(run);
  MetricResult metric = MakeMetric("free_fall.height", "m");
  const auto height = [&](const Sample& sample) {
    return sample.bodies[static_cast<std::size_t>(truth.body)].centerOfMass.dot(up);
  };
  // Two schemes are exact here: symplectic Euler lands on its own sequence,
  // a scheme exact for constant acceleration (velocity Verlet) on the
  // parabola itself. The run is judged against the one its last judged
  // sample (the last before `until`) is nearer to; either way a solver that
  // disturbs free flight misses both.
  const Sample* judged = &trajectory.samples.front();
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.until) break;
    judged = &sample;
  }
  const Sample& last = *judged;
  const bool continuous =
      std::abs(height(last) - FreeFallHeight(kind.y0, kind.v0, kind.g, last.time)) <
      std::abs(height(last) -
               FreeFallHeightSymplecticEuler(kind.y0, kind.v0, kind.g, trajectory.timeStep, last.step));
  double worst = -1.0;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.until) break;
    const double parabola = FreeFallHeight(kind.y0, kind.v0, kind.g, sample.time);
    const double exact = continuous ? parabola
                                    : FreeFallHeightSymplecticEuler(kind.y0, kind.v0, kind.g,
                                                                    trajectory.timeStep, sample.step);
    const double deviation = std::abs(height(sample) - exact);
    // !(deviation <= worst) also picks a NaN height, so it is not hidden.
    if (!(deviation <= worst)) {
      worst = std::isnan(deviation) ? INFINITY : deviation;
      metric.measured = height(sample);
      metric.truth = parabola;
      metric.truthIntegrator = continuous ? NAN : exact;
    }
  }
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
