// Rest height: the centre of mass height along the up axis at the end of the
// run against the stated height, and its jitter: the peak-to-peak height
// over the samples in the second half of the run (time >= duration / 2),
// which must stay below maxJitter. The jitter is always checked, with
// maxJitter as its absolute tolerance.
#include <algorithm>
#include <cassert>
#include <limits>

#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view RestHeightTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "height",
    "maxJitter"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "height": {
      "type": "number"
    },
    "maxJitter": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres: the largest peak-to-peak height over the second half of the run; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    }
  }
})json";
}

Result<RestHeightTruth> RestHeightTruth::Read(TruthReader& reader) {
  RestHeightTruth truth;
  truth.height = reader.Number("height");
  truth.maxJitter = reader.Bound("maxJitter");
  return truth;
}

void RestHeightTruth::Write(TruthWriter& writer) const {
  writer.out["height"] = height;
  writer.Bound("maxJitter", maxJitter);
}

std::vector<MetricResult> RestHeightTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const RestHeightTruth& kind,
                                                    const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Vec3 up = UpAxis(run);
  MetricResult height = MakeMetric("rest_height.height", "m");
  height.measured = trajectory.samples.back().bodies[body].centerOfMass.dot(up);
  height.truth = kind.height;
  Judge(height, truth.tolerance);

  const double halfTime = 0.5 * trajectory.samples.back().time;
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time < halfTime) continue;
    const double y = sample.bodies[body].centerOfMass.dot(up);
    low = MinKeepingNaN(low, y);
    high = MaxKeepingNaN(high, y);
  }
  MetricResult jitter = MakeMetric("rest_height.jitter", "m");
  // The last sample always qualifies; a NaN sample makes this NaN (a fail).
  jitter.measured = high - low;
  jitter.truth = 0.0;
  Judge(jitter, Tolerance{.absolute = kind.maxJitter, .relative = 0.0});
  jitter.reason = BoundReason(truth, "maxJitter");
  return {height, jitter};
}

}  // namespace talus::harness
