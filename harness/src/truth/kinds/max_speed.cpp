// Max speed: no listed body's centre of mass moves faster than the
// tolerance (m/s, absolute) over the window [from, until]. The metric,
// max_speed.<from>s_to_<until>s (the window in its name, so that a scene
// can bound the push-out over the whole run and the rest at its end with
// two truths whose metrics stay apart), is the largest speed over the
// listed bodies and the recorded samples in the window; its truth is 0.
// It is the bound a scene states from its physics: overlapping bodies
// pushed apart must not be thrown faster than the correction needs, a pile
// at the end must be still.
#include <cmath>
#include <limits>

#include "support/text_util.h"
#include "talus/harness/support/nan_extremes.h"
#include "talus/harness/support/number_text.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view MaxSpeedTruth::Schema() {
  return R"json({
  "required": [],
  "properties": {
    "bodies": {
      "type": "array",
      "minItems": 1,
      "items": {"type": "string"},
      "description": "names of the dynamic bodies whose speed is bounded, each once; default every dynamic body"
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
    }
  },
  "toleranceDescription": "required: absolute, in m/s: the fastest a listed body's centre of mass may move in the window, with the physical reason for that size"
})json";
}

Result<MaxSpeedTruth> MaxSpeedTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "m/s")) return *refused;
  auto bodies = ReadDynamicBodies(reader, "bodies");
  if (!bodies) return bodies.GetError();
  if (bodies.Value().empty()) return reader.Refuse("/kind", "max_speed needs a dynamic body");
  auto window = ReadTimeWindow(reader, "from", "until");
  if (!window) return window.GetError();
  return MaxSpeedTruth{std::move(bodies).Value(), window.Value().from, window.Value().until};
}

void MaxSpeedTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (int body : bodies) names.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
  writer.out["bodies"] = names;
  writer.out["from"] = from;
  writer.out["until"] = until;
}

std::vector<MetricResult> MaxSpeedTruth::Evaluate(const Run&, const Truth& truth, const MaxSpeedTruth& kind,
                                                  const Trajectory& trajectory) {
  // Half a step of slack at each end: a run at another time step (a sweep)
  // samples either side of the window's edges.
  const double slack = 0.5 * trajectory.timeStep;
  // -infinity until a sample is in the window: a run that stopped before
  // the window (a failed step) measures nothing and fails.
  double fastest = -std::numeric_limits<double>::infinity();
  for (const Sample& sample : trajectory.samples) {
    if (sample.time < kind.from - slack || sample.time > kind.until + slack) continue;
    for (int index : kind.bodies) {
      fastest = MaxKeepingNaN(fastest, sample.bodies[static_cast<std::size_t>(index)].linearVelocity.norm());
    }
  }
  MetricResult metric = MakeMetric(
      Concat({"max_speed.", FormatNumber(kind.from), "s_to_", FormatNumber(kind.until), "s"}), "m/s");
  metric.measured = std::isinf(fastest) ? std::nan("") : fastest;
  metric.truth = 0.0;
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
