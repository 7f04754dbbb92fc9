// Momentum conserved: with no gravity and no static body, nothing outside
// the listed bodies (every dynamic body when none are listed) pushes them,
// so their total linear momentum sum m v stays at its start through every
// collision among them (Newton's third law; a zero-gravity Newton's cradle
// passes it along the row). An impulse applied to one body of a pair only,
// or a position correction that feeds velocity, changes it. The metric,
// momentum_conserved.drift, is the largest |P(t) - P(0)| over the recorded
// samples, in kg m/s; its truth is 0 and the tolerance absolute.
#include <cmath>

#include "support/text_util.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view MomentumConservedTruth::Schema() {
  return R"json({
  "required": [],
  "properties": {
    "bodies": {
      "type": "array",
      "minItems": 1,
      "items": {"type": "string"},
      "description": "names of the dynamic bodies whose momentum is summed, each once; default every dynamic body"
    }
  },
  "toleranceDescription": "required: absolute, in kg m/s: how far the total linear momentum may move from its start, with the physical reason for that size"
})json";
}

Result<MomentumConservedTruth> MomentumConservedTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "kg m/s")) return *refused;
  if (!reader.world.gravity.isZero()) {
    return reader.Refuse("/kind",
                         "momentum_conserved needs a world without "
                         "gravity (gravity adds momentum)");
  }
  if (auto refused = RefuseStaticBodies(reader, "momentum_conserved")) return *refused;
  auto bodies = ReadDynamicBodies(reader, "bodies");
  if (!bodies) return bodies.GetError();
  return MomentumConservedTruth{std::move(bodies).Value()};
}

void MomentumConservedTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (int body : bodies) names.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
  writer.out["bodies"] = names;
}

std::vector<MetricResult> MomentumConservedTruth::Evaluate(const Run&, const Truth& truth,
                                                           const MomentumConservedTruth& kind,
                                                           const Trajectory& trajectory) {
  const auto momentum = [&](const Sample& sample) {
    Vec3 total = Vec3::Zero();
    for (int index : kind.bodies) {
      const BodyReading& body = sample.bodies[static_cast<std::size_t>(index)];
      total += body.mass * body.linearVelocity;
    }
    return total;
  };
  const Vec3 initial = momentum(trajectory.samples.front());
  double drift = 0.0;
  for (const Sample& sample : trajectory.samples) {
    drift = MaxKeepingNaN(drift, (momentum(sample) - initial).norm());
  }
  MetricResult metric = MakeMetric("momentum_conserved.drift", "kg m/s");
  metric.measured = drift;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
