// Energy not increasing: the total mechanical energy of the listed bodies
// (every dynamic body when none are listed), translational and rotational
// kinetic energy plus the potential -m g.(x - x0) measured from the start
// positions, never rises above its start. Contacts without restitution,
// friction and damping only take energy out and e = 1 at most keeps it, so
// a rise is energy the solver made (a position correction turned into
// speed, a warm start that overshoots). The metric,
// energy_not_increasing.rise, is the largest max(0, E(t) - E(0)) over the
// recorded samples, in joules; its truth is 0 and the tolerance absolute.
#include <algorithm>
#include <cmath>

#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view EnergyNotIncreasingTruth::Schema() {
  return R"json({
  "required": [],
  "properties": {
    "bodies": {
      "type": "array",
      "minItems": 1,
      "items": {"type": "string"},
      "description": "names of the dynamic bodies whose energy is summed, each once; default every dynamic body"
    }
  },
  "toleranceDescription": "required: absolute, in joules: how far the total energy may rise above its start, with the physical reason for that size"
})json";
}

Result<EnergyNotIncreasingTruth> EnergyNotIncreasingTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "joules")) return *refused;
  auto bodies = ReadDynamicBodies(reader, "bodies");
  if (!bodies) return bodies.GetError();
  if (bodies.Value().empty()) return reader.Refuse("/kind", "energy_not_increasing needs a dynamic body");
  return EnergyNotIncreasingTruth{std::move(bodies).Value()};
}

void EnergyNotIncreasingTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (int body : bodies) names.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
  writer.out["bodies"] = names;
}

std::vector<MetricResult> EnergyNotIncreasingTruth::Evaluate(const Run& run, const Truth& truth,
                                                             const EnergyNotIncreasingTruth& kind,
                                                             const Trajectory& trajectory) {
  const Vec3& g = run.scenario.world.gravity;
  const Sample& first = trajectory.samples.front();
  const auto energy = [&](const Sample& sample) {
    double total = 0.0;
    for (int index : kind.bodies) {
      const auto b = static_cast<std::size_t>(index);
      const BodyReading& body = sample.bodies[b];
      total += 0.5 * body.mass * body.linearVelocity.squaredNorm() +
               0.5 * body.angularVelocity.dot(body.worldInertia * body.angularVelocity) -
               body.mass * g.dot(body.centerOfMass - first.bodies[b].centerOfMass);
    }
    return total;
  };
  const double initial = energy(first);
  double rise = 0.0;
  for (const Sample& sample : trajectory.samples) rise = MaxKeepingNaN(rise, energy(sample) - initial);
  MetricResult metric = MakeMetric("energy_not_increasing.rise", "J");
  metric.measured = rise;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
