// Total energy drift: E = m v.v / 2 + w.I_world w / 2 - m g.x of the
// truth's body, or summed over every body when it names none (static
// bodies have no mass in the samples), over E0, the kinetic energy at the
// start: the total energy with the potential measured from the start
// positions, so the figure does not depend on where the potential's zero
// is (Peters and Hsu's "boxes" benchmark normalises the same way). The
// metric is the largest |E(t) - E(0)| / E0.
#include <algorithm>
#include <cmath>

#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

double Kinetic(const BodyReading& body) {
  return 0.5 * body.mass * body.linearVelocity.squaredNorm() +
         0.5 * body.angularVelocity.dot(body.worldInertia * body.angularVelocity);
}

}  // namespace

std::string_view EnergyDriftTruth::Schema() {
  return R"json({
  "required": [],
  "properties": {
    "body": {
      "type": "string",
      "description": "the body whose energy is summed; omitted: every body"
    }
  }
})json";
}

Result<EnergyDriftTruth> EnergyDriftTruth::Read(TruthReader& reader) {
  if (auto refused = RefuseStillStart(reader, "energy_drift", false)) return *refused;
  return EnergyDriftTruth{};
}

void EnergyDriftTruth::Write(TruthWriter& writer) const {
  (void)writer;  // no fields of its own
}

std::vector<MetricResult> EnergyDriftTruth::Evaluate(const Run& run, const Truth& truth,
                                                     const EnergyDriftTruth& kind,
                                                     const Trajectory& trajectory) {
  (void)kind;
  const Vec3& g = run.scenario.world.gravity;
  const Sample& first = trajectory.samples.front();
  const auto included = [&](std::size_t index) {
    return truth.body < 0 || index == static_cast<std::size_t>(truth.body);
  };
  // Energy relative to the start positions.
  const auto energy = [&](const Sample& sample) {
    double total = 0.0;
    for (std::size_t i = 0; i < sample.bodies.size(); ++i) {
      if (!included(i)) continue;
      const BodyReading& body = sample.bodies[i];
      total += Kinetic(body) - body.mass * g.dot(body.centerOfMass - first.bodies[i].centerOfMass);
    }
    return total;
  };
  const double initial = energy(first);
  double drift = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const double change = std::abs(energy(sample) - initial);
    if (!(change <= drift)) drift = std::isnan(change) ? INFINITY : change;
  }
  MetricResult metric = MakeMetric("energy_drift.relative", "");
  // The loader refuses a truth whose bodies all start at rest (E0 = 0).
  metric.measured = initial > 0.0 ? drift / initial : NAN;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
