// Topples: listed bodies fall, in the order listed. A body has toppled once
// its rotation from its start orientation (its tilt) reaches `angle` less
// the tolerance (radians, absolute: how far short still counts). Two
// metrics, each with truth 0 and judged with the tolerance:
// topples.shortfall, the largest over the bodies of max(0, angle - the
// body's largest tilt up to `within`), which a body left standing fails;
// topples.order, the largest over consecutive bodies i, i + 1 of
// max(0, angle - body i's largest tilt so far) at the first sample where
// body i + 1 has toppled, which a body falling before the one listed ahead
// of it fails (0 when each topples at the same sample as the body before it
// or later: the order is resolved to one sample).
#include <algorithm>
#include <cmath>
#include <limits>

#include "support/text_util.h"
#include "talus/harness/support/nan_extremes.h"
#include "talus/harness/support/number_text.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view TopplesTruth::Schema() {
  return R"json({
  "required": ["bodies", "angle"],
  "properties": {
    "bodies": {
      "type": "array",
      "minItems": 2,
      "items": {"type": "string"},
      "description": "names of the dynamic bodies in the order they must topple, each once"
    },
    "angle": {
      "type": "number",
      "exclusiveMinimum": 0,
      "maximum": 3.141592653589793,
      "description": "radians: the rotation from its start orientation at which a body has toppled; more than the tolerance"
    },
    "within": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "seconds: by when every body must have toppled, not after the run's end; default the run's end"
    }
  },
  "toleranceDescription": "required: absolute, in radians: how far short of the angle a body's tilt may stay and still count as toppled, with the physical reason for that size"
})json";
}

Result<TopplesTruth> TopplesTruth::Read(TruthReader& reader) {
  if (auto refused = RequireAbsoluteTolerance(reader, "radians")) return *refused;
  auto bodies = ReadDynamicBodies(reader, "bodies");
  if (!bodies) return bodies.GetError();
  auto window = ReadTimeWindow(reader, nullptr, "within");
  if (!window) return window.GetError();
  const double angle = reader.Number("angle");
  const double tolerance = reader.entry["tolerance"].value("absolute", 0.0);
  if (tolerance >= angle) {
    return reader.Refuse(
        "/tolerance/absolute",
        Concat({FormatNumber(tolerance), " rad is not below the angle (", FormatNumber(angle),
                " rad): every body would count as toppled where it starts"}));
  }
  return TopplesTruth{std::move(bodies).Value(), angle, window.Value().until};
}

void TopplesTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (int body : bodies) names.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
  writer.out["bodies"] = names;
  writer.out["angle"] = angle;
  writer.out["within"] = within;
}

std::vector<MetricResult> TopplesTruth::Evaluate(const Run&, const Truth& truth, const TopplesTruth& kind,
                                                 const Trajectory& trajectory) {
  const Sample& first = trajectory.samples.front();
  const double toppled = kind.angle - truth.tolerance.absolute;
  const double slack = 0.5 * trajectory.timeStep;  // a run at another step may end either side of `within`
  const std::size_t count = kind.bodies.size();
  std::vector<double> largest(count, 0.0);  // each body's largest tilt so far
  std::vector<bool> fallen(count, false);
  double order = 0.0;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.within + slack) break;
    for (std::size_t i = 0; i < count; ++i) {
      const auto b = static_cast<std::size_t>(kind.bodies[i]);
      largest[i] =
          MaxKeepingNaN(largest[i], RotationAngle(first.bodies[b].orientation, sample.bodies[b].orientation));
    }
    // After every body's tilt of this sample: two that topple at the same
    // sample are in order.
    for (std::size_t i = 1; i < count; ++i) {
      if (fallen[i] || !(largest[i] >= toppled)) continue;
      fallen[i] = true;
      order = MaxKeepingNaN(order, std::max(0.0, kind.angle - largest[i - 1]));
    }
  }
  double shortfall = 0.0;
  for (double tilt : largest) {
    // A NaN tilt (a body that blew up) makes the shortfall NaN: a fail.
    shortfall = MaxKeepingNaN(shortfall, std::isnan(tilt) ? tilt : std::max(0.0, kind.angle - tilt));
  }
  MetricResult shortfallMetric = MakeMetric("topples.shortfall", "rad");
  shortfallMetric.measured = shortfall;
  shortfallMetric.truth = 0.0;
  Judge(shortfallMetric, truth.tolerance);
  MetricResult orderMetric = MakeMetric("topples.order", "rad");
  orderMetric.measured = order;
  orderMetric.truth = 0.0;
  Judge(orderMetric, truth.tolerance);
  return {shortfallMetric, orderMetric};
}

}  // namespace talus::harness
