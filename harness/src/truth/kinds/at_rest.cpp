// At rest: listed bodies stay where they start over a window. Three
// metrics, each the worst over the listed bodies and the recorded samples
// inside [from, until]: at_rest.drift, the largest distance of a centre of
// mass from its position at the start of the run (metres, the truth's
// tolerance); at_rest.tilt, the largest rotation from the start
// orientation (radians, maxTilt); at_rest.speed, the largest centre-of-mass
// speed (m/s, maxSpeed), which catches a body that jitters in place. Each
// truth is 0, so a body that slides, tips, sinks or is thrown fails.
// Each name ends with the bodies it judges (at_rest.drift.left,right; past
// three bodies the first two and how many more: at_rest.drift.b0,b1,+15),
// so two at_rest truths of one scenario (a layer each, with its own
// allowance) report two metrics, not one name twice.
#include <cmath>
#include <limits>
#include <string>

#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view AtRestTruth::Schema() {
  return R"json({
  "required": ["bodies", "maxTilt", "maxSpeed"],
  "properties": {
    "bodies": {
      "type": "array",
      "minItems": 1,
      "items": {"type": "string"},
      "description": "names of the dynamic bodies that must stay at rest, each once"
    },
    "from": {
      "type": "number",
      "minimum": 0,
      "description": "seconds: start of the window judged; default 0"
    },
    "until": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "seconds: end of the window judged, after from and not after the run's end; default the run's end"
    },
    "maxTilt": {
      "type": "object",
      "additionalProperties": false,
      "required": ["value", "reason"],
      "properties": {
        "value": {"type": "number", "minimum": 0, "description": "rad"},
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "radians: the largest rotation of a listed body from its start orientation in the window; written {\"value\", \"reason\"}"
    },
    "maxSpeed": {
      "type": "object",
      "additionalProperties": false,
      "required": ["value", "reason"],
      "properties": {
        "value": {"type": "number", "minimum": 0, "description": "m/s"},
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "m/s: the largest centre-of-mass speed of a listed body in the window (jitter); written {\"value\", \"reason\"}"
    }
  },
  "toleranceDescription": "required: absolute, in metres: the largest distance a listed body's centre of mass may move from its start in the window, with the physical reason for that size"
})json";
}

Result<AtRestTruth> AtRestTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "metres")) return *refused;
  auto bodies = ReadDynamicBodies(reader, "bodies");
  if (!bodies) return bodies.GetError();
  auto window = ReadTimeWindow(reader, "from", "until");
  if (!window) return window.GetError();
  AtRestTruth truth;
  truth.bodies = std::move(bodies).Value();
  truth.from = window.Value().from;
  truth.until = window.Value().until;
  truth.maxTilt = reader.Bound("maxTilt");
  truth.maxSpeed = reader.Bound("maxSpeed");
  return truth;
}

void AtRestTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (int body : bodies) names.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
  writer.out["bodies"] = names;
  writer.out["from"] = from;
  writer.out["until"] = until;
  writer.Bound("maxTilt", maxTilt);
  writer.Bound("maxSpeed", maxSpeed);
}

std::vector<MetricResult> AtRestTruth::Evaluate(const Run& run, const Truth& truth, const AtRestTruth& kind,
                                                const Trajectory& trajectory) {
  const Sample& first = trajectory.samples.front();
  // Half a step of slack at each end: a run at another time step (a
  // sweep) ends at steps x h, which may round either side of `until`.
  const double slack = 0.5 * trajectory.timeStep;
  // -infinity until a sample is in the window: a run that stopped before
  // the window (a failed step) measures nothing and fails.
  double drift = -std::numeric_limits<double>::infinity();
  double tilt = drift;
  double speed = drift;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time < kind.from - slack || sample.time > kind.until + slack) continue;
    for (int index : kind.bodies) {
      const auto b = static_cast<std::size_t>(index);
      const BodyReading& now = sample.bodies[b];
      drift = MaxKeepingNaN(drift, (now.centerOfMass - first.bodies[b].centerOfMass).norm());
      tilt = MaxKeepingNaN(tilt, RotationAngle(first.bodies[b].orientation, now.orientation));
      speed = MaxKeepingNaN(speed, now.linearVelocity.norm());
    }
  }
  const auto unmeasured = [](double value) { return std::isinf(value) ? std::nan("") : value; };
  std::string judged;
  const std::size_t named = kind.bodies.size() > 3 ? 2 : kind.bodies.size();
  for (std::size_t i = 0; i < named; ++i) {
    judged += (i == 0 ? "." : ",") + run.scenario.bodies[static_cast<std::size_t>(kind.bodies[i])].name;
  }
  if (named < kind.bodies.size()) judged += ",+" + std::to_string(kind.bodies.size() - named);
  MetricResult driftMetric = MakeMetric("at_rest.drift" + judged, "m");
  driftMetric.measured = unmeasured(drift);
  driftMetric.truth = 0.0;
  Judge(driftMetric, truth.tolerance);
  MetricResult tiltMetric = MakeMetric("at_rest.tilt" + judged, "rad");
  tiltMetric.measured = unmeasured(tilt);
  tiltMetric.truth = 0.0;
  Judge(tiltMetric, Tolerance{.absolute = kind.maxTilt, .relative = 0.0});
  tiltMetric.reason = BoundReason(truth, "maxTilt");
  MetricResult speedMetric = MakeMetric("at_rest.speed" + judged, "m/s");
  speedMetric.measured = unmeasured(speed);
  speedMetric.truth = 0.0;
  Judge(speedMetric, Tolerance{.absolute = kind.maxSpeed, .relative = 0.0});
  speedMetric.reason = BoundReason(truth, "maxSpeed");
  return {driftMetric, tiltMetric, speedMetric};
}

}  // namespace talus::harness
