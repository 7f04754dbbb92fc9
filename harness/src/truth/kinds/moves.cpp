// Moves: a negative test. `body`'s centre of mass must get at least
// `distance` metres from where it started by `within` seconds: a structure
// with no equilibrium (an arch below its friction threshold, a tower past
// its tipping point) must fall, and an engine that holds it up by a
// solver artefact (too much friction, a stiff warm start) fails. The metric,
// moves.shortfall.<body>, is max(0, distance - the largest displacement over the
// recorded samples up to `within`); its truth is 0 and the tolerance
// (metres, absolute) is how far short still counts.
#include <algorithm>
#include <cmath>

#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view MovesTruth::Schema() {
  return R"json({
  "required": ["body", "distance", "within"],
  "properties": {
    "body": {"type": "string"},
    "distance": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "metres: how far the centre of mass must get from its start"
    },
    "within": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "seconds: by when, not after the run's end"
    }
  },
  "toleranceDescription": "required: absolute, in metres: how far short of the distance still counts as moved, with the physical reason for that size"
})json";
}

Result<MovesTruth> MovesTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "metres")) return *refused;
  if (reader.bodies[reader.body].motion != Motion::Dynamic) {
    return reader.Refuse("/body", "moves needs a dynamic body (a static one never moves)");
  }
  auto window = ReadTimeWindow(reader, nullptr, "within");
  if (!window) return window.GetError();
  return MovesTruth{reader.Number("distance"), window.Value().until};
}

void MovesTruth::Write(TruthWriter& writer) const {
  writer.out["distance"] = distance;
  writer.out["within"] = within;
}

std::vector<MetricResult> MovesTruth::Evaluate(const Run& run, const Truth& truth, const MovesTruth& kind,
                                               const Trajectory& trajectory) {
  const auto body = static_cast<std::size_t>(truth.body);
  const Vec3 start = trajectory.samples.front().bodies[body].centerOfMass;
  const double slack = 0.5 * trajectory.timeStep;  // a run at another step may end either side of `within`
  double farthest = 0.0;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.within + slack) break;
    farthest = MaxKeepingNaN(farthest, (sample.bodies[body].centerOfMass - start).norm());
  }
  MetricResult shortfall = MakeMetric("moves.shortfall." + run.scenario.bodies[body].name, "m");
  // A NaN position makes this NaN: a body that blew up has not "moved".
  shortfall.measured = std::isnan(farthest) ? farthest : std::max(0.0, kind.distance - farthest);
  shortfall.truth = 0.0;
  Judge(shortfall, truth.tolerance);
  return {shortfall};
}

}  // namespace talus::harness
