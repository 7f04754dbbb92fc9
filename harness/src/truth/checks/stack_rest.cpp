// Stack rest: for every box of every layer, the height of its centre of
// mass along the up axis at the end of the run against floor + (layer +
// 1/2) layerHeight (truths.h), one metric per box named by layer and body,
// judged with (layer + 1) times the truth's absolute tolerance: the file
// gives the depth one contact may rest at, and a box in layer l stands on
// l + 1 of them (the floor's and one per layer below), whose depths add;
// then one drift metric: the largest displacement of any listed box between
// the first sample of the second half of the run (time >= duration / 2) and
// the last, checked against maxDrift. A stack that creeps sideways or sinks
// slowly passes the heights at any instant but fails the drift.
#include <algorithm>
#include <cassert>
#include <string>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateStackRest(const Run& run, const Truth& truth, const StackRestTruth& kind,
                                            const Trajectory& trajectory) {
  const Vec3 up = UpAxis(run);
  const Sample& last = trajectory.samples.back();
  const double halfTime = 0.5 * last.time;
  const Sample* middle = &last;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time >= halfTime) {
      middle = &sample;
      break;
    }
  }
  std::vector<MetricResult> metrics;
  double drift = 0.0;
  for (size_t layer = 0; layer < kind.layers.size(); ++layer) {
    for (const int index : kind.layers[layer]) {
      assert(index >= 0 && index < static_cast<int>(last.bodies.size()));
      const auto body = static_cast<std::size_t>(index);
      MetricResult height = MakeMetric(
          "stack_rest.height." + std::to_string(layer) + "." + run.scenario.bodies[body].name, "m");
      height.measured = last.bodies[body].centerOfMass.dot(up);
      height.truth = StackRestHeight(kind.floor, kind.layerHeight, static_cast<int>(layer));
      // Layer l stands on l + 1 contacts (the floor's and one per layer
      // below), each of which may rest up to the tolerance deep.
      Tolerance perLayer = truth.tolerance;
      perLayer.absolute *= static_cast<double>(layer + 1);
      Judge(height, perLayer);
      metrics.push_back(height);
      drift =
          MaxKeepingNaN(drift, (last.bodies[body].centerOfMass - middle->bodies[body].centerOfMass).norm());
    }
  }
  MetricResult driftMetric = MakeMetric("stack_rest.drift", "m");
  driftMetric.measured = drift;
  driftMetric.truth = 0.0;
  Judge(driftMetric, Tolerance{.absolute = kind.maxDrift, .relative = 0.0});
  driftMetric.reason = BoundReason(truth, "maxDrift");
  metrics.push_back(driftMetric);
  return metrics;
}

}  // namespace talus::harness
