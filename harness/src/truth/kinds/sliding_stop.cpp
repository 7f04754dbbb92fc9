// Sliding stop: how far the centre of mass travelled across the floor (its
// displacement perpendicular to the up axis, first sample to last) against
// v0^2 / (2 mu g) and the symplectic-Euler sum (truths.h). The run must be
// long enough for the body to stop. Two more metrics: the stop time, the
// first sample whose speed across the floor is below kStoppedSpeed, against
// the time the exact slide's speed falls below it, (v0 - kStoppedSpeed) /
// (mu g), and the first step of the clamped symplectic-Euler slide below it
// (like for like: at small steps the threshold is crossed several steps
// before the speed reaches zero), judged with the same tolerance plus one
// sample interval (a strided trajectory sees the crossing up to one sample
// late); and the lateral deviation, the
// largest distance of the centre of mass from the launch line (start point,
// truth direction) across the floor, checked against maxLateral: a
// pyramid friction cone (ODE) bends paths launched off its axes.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

// |cos| of the angle between a sliding direction and gravity above which the
// direction is not horizontal: 1e-6 accepts directions written to ~7 digits.
constexpr double kPerpendicularTolerance = 1e-6;

// Speed (m/s) below which a sliding body counts as stopped: iterative
// solvers leave residual speeds of mm/s. The truths are the times the
// slide's speed falls below it, so it is compared like for like at any step
// (from 1 cm/s friction still needs 0.01 / (mu g), up to 3.4 ms at mu 0.3:
// under one 60 Hz step, but two at 1/480 s).
constexpr double kStoppedSpeed = 0.01;

}  // namespace

std::string_view SlidingStopTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "v0",
    "mu",
    "g",
    "maxLateral"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "v0": {
      "type": "number",
      "exclusiveMinimum": 0
    },
    "mu": {
      "type": "number",
      "exclusiveMinimum": 0
    },
    "g": {
      "type": "number",
      "exclusiveMinimum": 0
    },
    "direction": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "launch direction, perpendicular to gravity, any length > 0 (normalised); default [1, 0, 0]"
    },
    "maxLateral": {
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
          "description": "m, largest allowed distance of the centre of mass from the launch line; default 0.01"
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres: the largest allowed distance from the launch line; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    }
  }
})json";
}

Result<SlidingStopTruth> SlidingStopTruth::Read(TruthReader& reader) {
  SlidingStopTruth truth{reader.Number("v0"), reader.Number("mu"), reader.Number("g")};
  if (reader.Has("direction")) {
    const Vec3 direction = reader.Vector("direction");
    if (ScaleSafeNorm(direction) < 1e-12) return reader.Refuse("/direction", "direction has zero length");
    truth.direction = ScaleSafeNormalized(direction);
    if (std::abs(truth.direction.dot(ScaleSafeNormalized(reader.world.gravity))) > kPerpendicularTolerance) {
      return reader.Refuse("/direction", "must be perpendicular to gravity");
    }
  }
  truth.maxLateral = reader.Bound("maxLateral");
  return truth;
}

void SlidingStopTruth::Write(TruthWriter& writer) const {
  writer.out["v0"] = v0;
  writer.out["mu"] = mu;
  writer.out["g"] = g;
  writer.Vector("direction", direction);
  writer.Bound("maxLateral", maxLateral);
}

std::vector<MetricResult> SlidingStopTruth::Evaluate(const Run& run, const Truth& truth,
                                                     const SlidingStopTruth& kind,
                                                     const Trajectory& trajectory) {
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
    lateral = MaxKeepingNaN(lateral, across.norm());
  }
  time.truth = SlidingSlowTime(kind.v0, kind.mu, kind.g, kStoppedSpeed);
  time.truthIntegrator =
      SlidingSlowTimeSymplecticEuler(kind.v0, kind.mu, kind.g, trajectory.timeStep, kStoppedSpeed);
  // Samples are `stride` steps apart, so the first one below kStoppedSpeed
  // can come up to one sample interval after the step that crossed it: one
  // sample interval is added to the file's tolerance.
  Tolerance timeTolerance = truth.tolerance;
  timeTolerance.absolute += trajectory.timeStep * trajectory.stride;
  Judge(time, timeTolerance);
  MetricResult deviation = MakeMetric("sliding_stop.lateral", "m");
  deviation.measured = lateral;
  deviation.truth = 0.0;
  Judge(deviation, Tolerance{.absolute = kind.maxLateral, .relative = 0.0});
  deviation.reason = BoundReason(truth, "maxLateral");
  return {metric, time, deviation};
}

}  // namespace talus::harness
