// Projectile: the centre of mass against the parabola x0 + v0 t + g t^2 / 2
// on all three axes, g the world's gravity vector. The metric is the
// largest distance from it over the recorded samples (a 3D distance bounds
// every axis: a sideways drift the vertical-only free_fall cannot see
// counts here). Judged against the continuous answer: symplectic Euler's
// lag g h t / 2 along gravity is part of the error, and the scenario's
// tolerance says how much of it is allowed.
#include <cassert>
#include <cmath>

#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateProjectile(const Run& run, const Truth& truth, const ProjectileTruth& kind,
                                             const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const Vec3& g = run.scenario.world.gravity;
  double worst = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const double t = sample.time;
    const Vec3 parabola = kind.x0 + kind.v0 * t + 0.5 * g * t * t;
    const double distance =
        (sample.bodies[static_cast<std::size_t>(truth.body)].centerOfMass - parabola).norm();
    // !(distance <= worst) also picks a NaN position, so it is not hidden.
    if (!(distance <= worst)) worst = std::isnan(distance) ? INFINITY : distance;
  }
  MetricResult metric = MakeMetric("projectile.position_error", "m");
  metric.measured = worst;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
