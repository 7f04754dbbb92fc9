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
#include <unordered_set>

#include "support/text_util.h"
#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view StackRestTruth::Schema() {
  return R"json({
  "required": [
    "layers",
    "floor",
    "layerHeight",
    "maxDrift"
  ],
  "properties": {
    "layers": {
      "type": "array",
      "minItems": 1,
      "description": "body names per layer, bottom layer first",
      "items": {
        "type": "array",
        "minItems": 1,
        "items": {
          "type": "string"
        }
      }
    },
    "floor": {
      "type": "number",
      "description": "m, height of the floor's top along the up axis"
    },
    "layerHeight": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "m, height of one layer"
    },
    "maxDrift": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0,
          "description": "m, largest allowed displacement of any listed body over the second half of the run; default 0.01"
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "metres: the largest displacement of any listed box over the second half of the run; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    }
  }
})json";
}

Result<StackRestTruth> StackRestTruth::Read(TruthReader& reader) {
  StackRestTruth truth;
  truth.floor = reader.Number("floor");
  truth.layerHeight = reader.Number("layerHeight");
  truth.maxDrift = reader.Bound("maxDrift");
  std::unordered_set<int> seen;
  const nlohmann::json& layers = reader.entry["layers"];
  for (size_t l = 0; l < layers.size(); ++l) {
    std::vector<int> layer;
    for (size_t k = 0; k < layers[l].size(); ++k) {
      const std::string where = "/layers/" + std::to_string(l) + "/" + std::to_string(k);
      const std::string name = layers[l][k].get<std::string>();
      const int body = reader.FindBody(name);
      if (body < 0) return reader.Refuse(where, "no body named " + Quoted(name));
      if (seen.count(body) != 0) return reader.Refuse(where, "body " + Quoted(name) + " is listed twice");
      if (reader.bodies[body].motion != Motion::Dynamic) {
        return reader.Refuse(where, "body " + Quoted(name) + " is static");
      }
      seen.insert(body);
      layer.push_back(body);
    }
    truth.layers.push_back(std::move(layer));
  }
  return truth;
}

void StackRestTruth::Write(TruthWriter& writer) const {
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (const auto& layer : layers) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (int body : layer) row.push_back(writer.bodies[static_cast<std::size_t>(body)].name);
    names.push_back(row);
  }
  writer.out["layers"] = names;
  writer.out["floor"] = floor;
  writer.out["layerHeight"] = layerHeight;
  writer.Bound("maxDrift", maxDrift);
}

std::vector<MetricResult> StackRestTruth::Evaluate(const Run& run, const Truth& truth,
                                                   const StackRestTruth& kind, const Trajectory& trajectory) {
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
