// State at a time: `body`'s centre of mass position or velocity, or its
// orientation, at `time` seconds against the file's value (a closed form
// the author derived, e.g. a rolling sphere's s = 5/14 g sin(theta) t^2).
// The metric is the distance between the two (state_at.position.<body>
// in m, state_at.velocity.<body> in m/s) or the angle of the rotation from
// one to the other (state_at.orientation.<body>, rad); its truth is 0 and the tolerance is
// absolute. Between two recorded samples the state is interpolated
// (linearly; slerp for an orientation), so a strided trajectory is judged
// at the stated time too.
#include <cmath>

#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/support/number_text.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

const char* QuantityName(StateQuantity quantity) {
  switch (quantity) {
    case StateQuantity::Position:
      return "position";
    case StateQuantity::Velocity:
      return "velocity";
    case StateQuantity::Orientation:
      return "orientation";
  }
  return "position";
}

}  // namespace

std::string_view StateAtTruth::Schema() {
  return R"json({
  "required": ["body", "quantity", "time", "value"],
  "properties": {
    "body": {"type": "string"},
    "quantity": {
      "enum": ["position", "velocity", "orientation"],
      "description": "position: the centre of mass (m, world); velocity: its velocity (m/s, world); orientation: the body frame's"
    },
    "time": {
      "type": "number",
      "minimum": 0,
      "description": "seconds: when, not after the run's end"
    },
    "value": {
      "type": "array",
      "items": {"type": "number"},
      "minItems": 3,
      "maxItems": 4,
      "description": "[x, y, z] for a position or velocity; a unit quaternion [w, x, y, z] for an orientation"
    }
  },
  "toleranceDescription": "required: absolute, in the quantity's unit (m, m/s, or rad for an orientation): how far the state may be from the value, with the physical reason for that size"
})json";
}

Result<StateAtTruth> StateAtTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "in the quantity's unit")) return *refused;
  if (reader.bodies[reader.body].motion != Motion::Dynamic) {
    return reader.Refuse("/body", "state_at needs a dynamic body (a static one keeps its state)");
  }
  StateAtTruth truth;
  const std::string quantity = reader.Text("quantity");
  truth.quantity = quantity == "velocity"      ? StateQuantity::Velocity
                   : quantity == "orientation" ? StateQuantity::Orientation
                                               : StateQuantity::Position;
  truth.time = reader.Number("time");
  if (truth.time > reader.Duration()) {
    return reader.Refuse("/time", FormatNumber(truth.time) +
                                      " s is after the end of the run (the run ends at " +
                                      FormatNumber(reader.Duration()) + " s)");
  }
  const nlohmann::json& value = reader.entry["value"];
  const std::size_t wanted = truth.quantity == StateQuantity::Orientation ? 4 : 3;
  if (value.size() != wanted) {
    return reader.Refuse("/value", wanted == 4 ? "an orientation is a quaternion [w, x, y, z]"
                                               : "a position or velocity is [x, y, z]");
  }
  if (wanted == 3) {
    truth.value = reader.Vector("value");
    return truth;
  }
  truth.orientation = Eigen::Vector4d(value[0].get<double>(), value[1].get<double>(), value[2].get<double>(),
                                      value[3].get<double>());
  if (std::abs(truth.orientation.norm() - 1.0) > kUnitQuaternionTolerance) {
    return reader.Refuse(
        "/value", "quaternion is not unit length (norm " + FormatNumber(truth.orientation.norm()) + ")");
  }
  return truth;
}

void StateAtTruth::Write(TruthWriter& writer) const {
  writer.out["quantity"] = QuantityName(quantity);
  writer.out["time"] = time;
  if (quantity == StateQuantity::Orientation) {
    writer.out["value"] = {orientation[0], orientation[1], orientation[2], orientation[3]};
  } else {
    writer.Vector("value", value);
  }
}

std::vector<MetricResult> StateAtTruth::Evaluate(const Run& run, const Truth& truth, const StateAtTruth& kind,
                                                 const Trajectory& trajectory) {
  const auto body = static_cast<std::size_t>(truth.body);
  // The last sample at or before `time` and the one after it (the same
  // sample when `time` is recorded, or is past the last sample of a run
  // that stopped early: then the metric is NaN).
  std::size_t after = 0;
  while (after + 1 < trajectory.samples.size() && trajectory.samples[after].time < kind.time) ++after;
  const Sample& high = trajectory.samples[after];
  const Sample& low = after > 0 && high.time > kind.time ? trajectory.samples[after - 1] : high;
  const bool reached = high.time >= kind.time - 0.5 * trajectory.timeStep;
  const double span = high.time - low.time;
  const double w = span > 0.0 ? (kind.time - low.time) / span : 0.0;
  const BodyReading& a = low.bodies[body];
  const BodyReading& b = high.bodies[body];
  MetricResult metric = MakeMetric(
      std::string("state_at.") + QuantityName(kind.quantity) + "." + run.scenario.bodies[body].name,
      kind.quantity == StateQuantity::Orientation ? "rad"
      : kind.quantity == StateQuantity::Velocity  ? "m/s"
                                                  : "m");
  switch (kind.quantity) {
    case StateQuantity::Position:
      metric.measured = ((1.0 - w) * a.centerOfMass + w * b.centerOfMass - kind.value).norm();
      break;
    case StateQuantity::Velocity:
      metric.measured = ((1.0 - w) * a.linearVelocity + w * b.linearVelocity - kind.value).norm();
      break;
    case StateQuantity::Orientation: {
      const Quat expected(kind.orientation[0], kind.orientation[1], kind.orientation[2], kind.orientation[3]);
      metric.measured = RotationAngle(a.orientation.slerp(w, b.orientation), expected);
      break;
    }
  }
  if (!reached) metric.measured = std::nan("");  // the run stopped before `time`
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
