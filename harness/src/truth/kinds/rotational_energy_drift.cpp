// Rotational energy drift of a free body: E = w.I_world w / 2, the largest
// |E(t) - E(0)| / E(0) over the samples. A scheme that conserves L can still
// err here (a splitting's energy error is O((h w)^2), bounded), and an
// implicit step that damps loses both: hence a tolerance of its own.
#include <cassert>
#include <cmath>

#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view RotationalEnergyDriftTruth::Schema() {
  return R"json({
  "required": [
    "body"
  ],
  "properties": {
    "body": {
      "type": "string"
    }
  }
})json";
}

Result<RotationalEnergyDriftTruth> RotationalEnergyDriftTruth::Read(TruthReader& reader) {
  if (auto refused = RefuseStillStart(reader, "rotational_energy_drift", true)) return *refused;
  return RotationalEnergyDriftTruth{};
}

void RotationalEnergyDriftTruth::Write(TruthWriter& writer) const {
  (void)writer;  // no fields of its own
}

std::vector<MetricResult> RotationalEnergyDriftTruth::Evaluate(const Run& run, const Truth& truth,
                                                               const RotationalEnergyDriftTruth& kind,
                                                               const Trajectory& trajectory) {
  (void)run;
  (void)kind;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const auto energy = [body](const Sample& sample) {
    const BodyReading& state = sample.bodies[body];
    return 0.5 * state.angularVelocity.dot(state.worldInertia * state.angularVelocity);
  };
  const double initial = energy(trajectory.samples.front());
  double drift = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const double change = std::abs(energy(sample) - initial);
    if (!(change <= drift)) drift = std::isnan(change) ? INFINITY : change;
  }
  MetricResult metric = MakeMetric("rotational_energy_drift.relative", "");
  // The loader refuses a body that starts without spin (E(0) = 0).
  metric.measured = initial > 0.0 ? drift / initial : NAN;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
