// Projectile: free flight on all three axes, judged per axis.
// - Along gravity (projectile.along_gravity): the height along the up axis
//   against the closed form of a correct integrator of constant gravity that
//   the run follows best, as free_fall does (FreeFallTruth::Evaluate): the parabola
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

#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view ProjectileTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "x0",
    "v0"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "x0": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "m, centre of mass at t = 0 (the body's position: box or sphere)"
    },
    "v0": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "m/s, the body's linearVelocity"
    }
  }
})json";
}

Result<ProjectileTruth> ProjectileTruth::Read(TruthReader& reader) {
  // The parabola starts where the body is: its centre of mass, which for a
  // box or a sphere is its origin, and its velocity.
  if (auto refused = RefuseStaticBodies(reader, "projectile")) return *refused;
  const BodySpec& body = reader.bodies[reader.body];
  if (body.motion != Motion::Dynamic || std::holds_alternative<HullShape>(body.shape)) {
    return reader.Refuse("/body",
                         "projectile needs a dynamic box or sphere (its centre of mass is its origin)");
  }
  const ProjectileTruth truth{reader.Vector("x0"), reader.Vector("v0")};
  if ((truth.x0 - body.position).norm() > kSpinConsistencyTolerance * (1.0 + body.position.norm())) {
    return reader.Refuse("/x0", "differs from the body's position");
  }
  if ((truth.v0 - body.linearVelocity).norm() >
      kSpinConsistencyTolerance * (1.0 + body.linearVelocity.norm())) {
    return reader.Refuse("/v0", "differs from the body's linearVelocity");
  }
  return truth;
}

void ProjectileTruth::Write(TruthWriter& writer) const {
  writer.Vector("x0", x0);
  writer.Vector("v0", v0);
}

std::vector<MetricResult> ProjectileTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const ProjectileTruth& kind,
                                                    const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const Vec3 up = UpAxis(run);
  const double g = run.scenario.world.gravity.dot(-up);
  const FreeFallTruth fall{kind.x0.dot(up), kind.v0.dot(up), g};
  std::vector<MetricResult> along = FreeFallTruth::Evaluate(run, truth, fall, trajectory);
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
