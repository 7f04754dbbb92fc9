// Flip period: the mean interval between successive sign changes of the
// intermediate-axis component of the body-frame angular velocity
// (w_body = q^-1 w_world, the scenario's body frame being the principal
// frame, which the loader checks for boxes), against
// IntermediateAxisFlipInterval (RK4 on Euler's equations, torque_free_motion.h).
// Crossing times are interpolated linearly between samples. Fewer than two
// crossings measure NaN and fail: the body never turned over (an engine
// without the gyroscopic term keeps spinning about the unstable axis).
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "talus/harness/analytic/torque_free_motion.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view FlipPeriodTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "inertia",
    "omega"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "inertia": {
      "type": "array",
      "items": {
        "type": "number",
        "exclusiveMinimum": 0
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "kg m^2, principal moments about the body axes x, y, z"
    },
    "omega": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "rad/s, initial angular velocity in the body frame"
    }
  }
})json";
}

Result<FlipPeriodTruth> FlipPeriodTruth::Read(TruthReader& reader) {
  auto spin = ReadSpinStart(reader);
  if (!spin) return spin.GetError();
  auto interval = IntermediateAxisFlipInterval(spin.Value().inertia, spin.Value().omega);
  if (!interval) return reader.Refuse("/omega", interval.GetError().message);
  return FlipPeriodTruth{spin.Value().inertia, spin.Value().omega};
}

void FlipPeriodTruth::Write(TruthWriter& writer) const {
  writer.Vector("inertia", inertia);
  writer.Vector("omega", omega);
}

std::vector<MetricResult> FlipPeriodTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const FlipPeriodTruth& kind,
                                                    const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const int axis = IntermediateAxis(kind.inertia);
  assert(axis >= 0 && "the loader refuses inertias without an intermediate axis");
  std::vector<double> crossings;
  double previous = 0.0;
  double previousTime = 0.0;
  for (size_t i = 0; i < trajectory.samples.size(); ++i) {
    const Sample& sample = trajectory.samples[i];
    const BodyReading& state = sample.bodies[body];
    const double component = (state.orientation.conjugate() * state.angularVelocity)[axis];
    if (i > 0 && (previous > 0.0) != (component > 0.0)) {
      const double fraction = previous / (previous - component);
      crossings.push_back(previousTime + fraction * (sample.time - previousTime));
    }
    previous = component;
    previousTime = sample.time;
  }
  MetricResult metric = MakeMetric("flip_period.interval", "s");
  metric.measured = crossings.size() >= 2
                        ? (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1)
                        : std::numeric_limits<double>::quiet_NaN();
  auto interval = IntermediateAxisFlipInterval(kind.inertia, kind.omega);
  assert(interval && "the loader checked that the truth has a flip interval");
  metric.truth = interval ? interval.Value() : std::numeric_limits<double>::quiet_NaN();
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
