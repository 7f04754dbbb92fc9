// Max penetration: no contact is deeper than the tolerance (metres,
// absolute), from `from` seconds on. The metric, max_penetration.depth, is
// the largest contact depth the backend reported at the recorded samples
// (Sample::maxPenetration: every step when the run is recorded at stride
// 1, else every stride-th step); its truth is 0. A solver that lets heavy
// bodies sink into light ones, or a stack that settles into its supports,
// fails it. `from` skips a start that overlaps on purpose.
#include <cmath>
#include <limits>

#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view MaxPenetrationTruth::Schema() {
  return R"json({
  "required": [],
  "properties": {
    "from": {
      "type": "number",
      "minimum": 0,
      "description": "seconds: judge contacts from here on, before the run's end; default 0"
    }
  },
  "toleranceDescription": "required: absolute, in metres: the deepest contact allowed, with the physical reason for that size (the engines' slop, the overlap one step of gravity makes)"
})json";
}

Result<MaxPenetrationTruth> MaxPenetrationTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "metres")) return *refused;
  auto window = ReadTimeWindow(reader, "from", nullptr);
  if (!window) return window.GetError();
  return MaxPenetrationTruth{window.Value().from};
}

void MaxPenetrationTruth::Write(TruthWriter& writer) const { writer.out["from"] = from; }

std::vector<MetricResult> MaxPenetrationTruth::Evaluate(const Run&, const Truth& truth,
                                                        const MaxPenetrationTruth& kind,
                                                        const Trajectory& trajectory) {
  const double slack = 0.5 * trajectory.timeStep;  // a run at another step samples either side of `from`
  double deepest = -std::numeric_limits<double>::infinity();
  for (const Sample& sample : trajectory.samples) {
    if (sample.step == 0 || sample.time < kind.from - slack) continue;  // step 0 has no contacts yet
    deepest = MaxKeepingNaN(deepest, sample.maxPenetration);
  }
  MetricResult metric = MakeMetric("max_penetration.depth", "m");
  // No sample in the window (a run that stopped early) measures nothing: NaN, a
  // fail.
  metric.measured = std::isinf(deepest) ? std::nan("") : deepest;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
