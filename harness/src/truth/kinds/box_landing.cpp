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

#include "truth/kinds/kind_support.h"

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

std::string_view BoxLandingTruth::Schema() {
  return R"json({
  "toleranceDescription": "required: metres: how far the centre of mass may rest from the geometric height floor + the half extent of the face-down axis, with the physical reason",
  "required": [
    "body",
    "floor",
    "restAfter",
    "maxFaceAngle",
    "maxMotion",
    "maxEnergyRise",
    "maxPenetration"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "floor": {
      "type": "number",
      "description": "metres: top of the floor along the up axis"
    },
    "restAfter": {
      "type": "number",
      "minimum": 0,
      "description": "seconds: the box must be at rest from here to the end of the run"
    },
    "maxFaceAngle": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0,
          "maximum": 0.7853981633974483
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "radians: the largest angle between the box axis nearest up and up at the end; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    },
    "maxMotion": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres: the largest peak-to-peak motion of the centre of mass along any world axis from restAfter to the end; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    },
    "maxEnergyRise": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres of lift: the largest rise of the total mechanical energy over its lowest earlier value, divided by m |g|; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    },
    "maxPenetration": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres: the deepest contact over the run; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    }
  }
})json";
}

Result<BoxLandingTruth> BoxLandingTruth::Read(TruthReader& reader) {
  // Judged on a dynamic box (its faces and half extents give the resting
  // heights) that comes to rest within the run.
  const BodySpec& body = reader.bodies[reader.body];
  if (body.motion != Motion::Dynamic || !std::holds_alternative<BoxShape>(body.shape)) {
    return reader.Refuse("/body", "box_landing needs a dynamic box body");
  }
  if (reader.world.gravity.isZero()) {
    return reader.Refuse("/kind", "box_landing needs gravity (nothing pulls the box down)");
  }
  BoxLandingTruth truth;
  truth.floor = reader.Number("floor");
  truth.restAfter = reader.Number("restAfter");
  if (truth.restAfter > reader.Duration()) return reader.Refuse("/restAfter", "is after the end of the run");
  truth.maxFaceAngle = reader.Bound("maxFaceAngle");
  truth.maxMotion = reader.Bound("maxMotion");
  truth.maxEnergyRise = reader.Bound("maxEnergyRise");
  truth.maxPenetration = reader.Bound("maxPenetration");
  return truth;
}

void BoxLandingTruth::Write(TruthWriter& writer) const {
  writer.out["floor"] = floor;
  writer.out["restAfter"] = restAfter;
  writer.Bound("maxFaceAngle", maxFaceAngle);
  writer.Bound("maxMotion", maxMotion);
  writer.Bound("maxEnergyRise", maxEnergyRise);
  writer.Bound("maxPenetration", maxPenetration);
}

std::vector<MetricResult> BoxLandingTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const BoxLandingTruth& kind,
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
