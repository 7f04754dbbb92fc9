// Projectile: free flight on all three axes, judged per axis.
// - Along gravity (projectile.along_gravity): the height along the up axis
//   against the closed form of a correct integrator of constant gravity that
//   the run follows best, as free_fall does (EvaluateFreeFall): the parabola
//   for a scheme exact for constant gravity, symplectic Euler's sequence
//   (g h t / 2 below it) for a first-order position update, explicit
//   Euler's. That lag is allowed only along gravity and only to a run that
//   follows that integrator: a run exact for gravity is held to the
//   parabola itself. The metric's truth is the parabola (what the sweep's
//   error axis reads) and its integrator truth the form it follows.
// - Across gravity (projectile.across_gravity): the largest distance of the
//   centre of mass, projected on the plane normal to gravity, from the
//   straight line x0 + v0 t projected the same way. No force acts there, so
//   every integrator owes it exactly: no allowance at all.
// Both are judged with the truth's tolerance (round-off).
#include <cassert>
#include <cmath>

#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateProjectile(const Run& run, const Truth& truth, const ProjectileTruth& kind,
                                             const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const Vec3 up = UpAxis(run);
  const double g = run.scenario.world.gravity.dot(-up);
  const FreeFallTruth fall{kind.x0.dot(up), kind.v0.dot(up), g};
  std::vector<MetricResult> along = EvaluateFreeFall(run, truth, fall, trajectory);
  along.front().name = "projectile.along_gravity";

  const auto across = [&](const Vec3& point) { return Vec3(point - point.dot(up) * up); };
  double worst = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const Vec3 line = kind.x0 + kind.v0 * sample.time;
    const double distance =
        (across(sample.bodies[static_cast<std::size_t>(truth.body)].centerOfMass) - across(line)).norm();
    // !(distance <= worst) also picks a NaN position, so it is not hidden.
    if (!(distance <= worst)) worst = std::isnan(distance) ? INFINITY : distance;
  }
  MetricResult sideways = MakeMetric("projectile.across_gravity", "m");
  sideways.measured = worst;
  sideways.truth = 0.0;
  Judge(sideways, truth.tolerance);
  return {along.front(), sideways};
}

}  // namespace talus::harness
