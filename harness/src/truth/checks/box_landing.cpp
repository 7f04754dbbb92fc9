// Box landing: a box thrown onto a static floor, judged on its own physics
// and not against a finer run of the same engine. At the end it must rest
// on a face: the box axis nearest the up axis within maxFaceAngle of it,
// and the centre of mass at floor + that axis's half extent (the geometric
// height, the truth's tolerance). From restAfter on, the centre of mass
// must move less than maxMotion along every world axis (peak to peak). The
// total mechanical energy (translational and rotational kinetic energy
// plus m |g| times the height gained) may only fall: a floor without
// restitution takes energy out and gives none back, so the largest rise
// over its lowest earlier value, in metres of lift (divided by m |g|),
// stays below maxEnergyRise. No contact is deeper than maxPenetration.
// A box that never lands fails the height, the face (most likely) and the
// rest; a box that lands and bounces back up fails the energy.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "truth/checks/evaluators.h"

namespace talus::harness {
namespace {

// The larger of `worst` and `value`, where a NaN wins and then stays (a NaN
// state is never hidden by a maximum).
double WorseOf(double worst, double value) {
  if (std::isnan(worst) || value <= worst) return worst;
  return value;  // larger, or NaN
}

double Energy(const BodyReading& body, const Vec3& up, double g) {
  return 0.5 * body.mass * body.linearVelocity.squaredNorm() +
         0.5 * body.angularVelocity.dot(body.worldInertia * body.angularVelocity) +
         body.mass * g * body.centerOfMass.dot(up);
}

}  // namespace

std::vector<MetricResult> EvaluateBoxLanding(const Run& run, const Truth& truth, const BoxLandingTruth& kind,
                                             const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Vec3& halfExtents = std::get<BoxShape>(run.scenario.bodies[body].shape).halfExtents;
  const Vec3 up = UpAxis(run);
  const double g = run.scenario.world.gravity.norm();
  const BodyReading& last = trajectory.samples.back().bodies[body];

  // The face down is the box axis nearest the up axis (either sign).
  const Mat3 axes = last.orientation.toRotationMatrix();
  int nearest = 0;
  for (int axis = 1; axis < 3; ++axis) {
    if (std::abs(axes.col(axis).dot(up)) > std::abs(axes.col(nearest).dot(up))) nearest = axis;
  }
  MetricResult face = MakeMetric("box_landing.face_angle", "rad");
  face.measured = std::acos(std::min(1.0, std::abs(axes.col(nearest).dot(up))));
  face.truth = 0.0;
  Judge(face, Tolerance{.absolute = kind.maxFaceAngle, .relative = 0.0});
  face.reason = BoundReason(truth, "maxFaceAngle");

  MetricResult height = MakeMetric("box_landing.height", "m");
  height.measured = last.centerOfMass.dot(up);
  height.truth = kind.floor + halfExtents[nearest];
  Judge(height, truth.tolerance);

  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  double energyFloor = std::numeric_limits<double>::infinity();
  double rise = 0.0;
  double deepest = 0.0;
  bool finiteAtRest = true;
  for (const Sample& sample : trajectory.samples) {
    const BodyReading& state = sample.bodies[body];
    if (sample.time >= kind.restAfter) {
      finiteAtRest = finiteAtRest && state.centerOfMass.allFinite();
      low = low.cwiseMin(state.centerOfMass);
      high = high.cwiseMax(state.centerOfMass);
    }
    const double energy = Energy(state, up, g);
    rise = WorseOf(rise, energy - energyFloor);
    energyFloor = std::min(energyFloor, energy);
    deepest = WorseOf(deepest, sample.maxPenetration);
  }
  MetricResult motion = MakeMetric("box_landing.motion", "m");
  // The last sample is always at or after restAfter (the loader refuses a
  // later one), so the range is finite unless a position is not.
  motion.measured = finiteAtRest ? (high - low).maxCoeff() : std::numeric_limits<double>::quiet_NaN();
  motion.truth = 0.0;
  Judge(motion, Tolerance{.absolute = kind.maxMotion, .relative = 0.0});
  motion.reason = BoundReason(truth, "maxMotion");

  MetricResult energy = MakeMetric("box_landing.energy_rise", "m");
  energy.measured = rise / (last.mass * g);
  energy.truth = 0.0;
  Judge(energy, Tolerance{.absolute = kind.maxEnergyRise, .relative = 0.0});
  energy.reason = BoundReason(truth, "maxEnergyRise");

  MetricResult penetration = MakeMetric("box_landing.penetration", "m");
  penetration.measured = deepest;
  penetration.truth = 0.0;
  Judge(penetration, Tolerance{.absolute = kind.maxPenetration, .relative = 0.0});
  penetration.reason = BoundReason(truth, "maxPenetration");
  return {height, face, motion, energy, penetration};
}

}  // namespace talus::harness
