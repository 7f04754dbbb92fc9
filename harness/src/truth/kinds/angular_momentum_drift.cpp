// Angular momentum drift of a free body: L = I_world w about its centre of
// mass, world frame, sampled along the run. "vector" measures
// max |L(t) - L(0)| / |L(0)| (a turned L counts), "magnitude" measures
// max ||L(t)| - |L(0)|| / |L(0)| (the figure benchmarks publish, e.g. Peters
// and Hsu's |dL|/L). Kept apart from the rotational energy so each has its
// own tolerance.
#include <cassert>
#include <cmath>

#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view AngularMomentumDriftTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "metric"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "metric": {
      "enum": [
        "vector",
        "magnitude"
      ],
      "description": "vector: max |L - L0| / |L0|; magnitude: max ||L| - |L0|| / |L0|"
    }
  }
})json";
}

Result<AngularMomentumDriftTruth> AngularMomentumDriftTruth::Read(TruthReader& reader) {
  if (auto refused = RefuseStillStart(reader, "angular_momentum_drift", true)) return *refused;
  return AngularMomentumDriftTruth{reader.Text("metric") == "magnitude" ? MomentumMetric::Magnitude
                                                                        : MomentumMetric::Vector};
}

void AngularMomentumDriftTruth::Write(TruthWriter& writer) const {
  writer.out["metric"] = metric == MomentumMetric::Magnitude ? "magnitude" : "vector";
}

std::vector<MetricResult> AngularMomentumDriftTruth::Evaluate(const Run& run, const Truth& truth,
                                                              const AngularMomentumDriftTruth& kind,
                                                              const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const auto momentum = [body](const Sample& sample) {
    const BodyReading& state = sample.bodies[body];
    return Vec3(state.worldInertia * state.angularVelocity);
  };
  const Vec3 initial = momentum(trajectory.samples.front());
  double drift = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const Vec3 now = momentum(sample);
    const double change = kind.metric == MomentumMetric::Vector ? (now - initial).norm()
                                                                : std::abs(now.norm() - initial.norm());
    if (!(change <= drift)) drift = std::isnan(change) ? INFINITY : change;
  }
  const bool vector = kind.metric == MomentumMetric::Vector;
  MetricResult metric =
      MakeMetric(vector ? "angular_momentum_drift.vector" : "angular_momentum_drift.magnitude", "");
  // The loader refuses a body that starts without spin (|L(0)| = 0).
  metric.measured = initial.norm() > 0.0 ? drift / initial.norm() : NAN;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
