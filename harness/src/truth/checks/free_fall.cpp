// Free fall: the centre of mass height along the up axis against the
// parabola y0 + v0 t - g t^2 / 2 and against the symplectic-Euler sequence
// (truths.h). The metric is taken at the recorded sample where the height
// strays furthest from the integrator's answer, so a deviation anywhere in
// the run is reported, not only at its end. Samples after `until` (a
// landing) are not judged.
#include <cassert>
#include <cmath>

#include "talus/harness/analytic/truths.h"
#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateFreeFall(const Run& run, const Truth& truth, const FreeFallTruth& kind,
                                           const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const Vec3 up = UpAxis(run);
  MetricResult metric = MakeMetric("free_fall.height", "m");
  double worst = -1.0;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.until) break;
    const double height = sample.bodies[static_cast<std::size_t>(truth.body)].centerOfMass.dot(up);
    const double exact =
        FreeFallHeightSymplecticEuler(kind.y0, kind.v0, kind.g, trajectory.timeStep, sample.step);
    const double deviation = std::abs(height - exact);
    // !(deviation <= worst) also picks a NaN height, so it is not hidden.
    if (!(deviation <= worst)) {
      worst = std::isnan(deviation) ? INFINITY : deviation;
      metric.measured = height;
      metric.truth = FreeFallHeight(kind.y0, kind.v0, kind.g, sample.time);
      metric.truthIntegrator = exact;
    }
  }
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
