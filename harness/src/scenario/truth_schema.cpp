// The truths' part of the scenario schema from the table of truth kinds
// (truth_schema.h).
#include "talus/harness/scenario/truth_schema.h"

#include <string_view>

#include "scenario/scenario_schema_text.h"
#include "talus/harness/scenario/truth_kinds.h"

namespace talus::harness {
namespace {

using nlohmann::ordered_json;

// The fields every truth entry may have, whatever its kind, read and
// written by the loader and the writer themselves. A kind's fragment may
// give the tolerance its own description ("toleranceDescription": what the
// tolerance means for that kind, e.g. its unit).
constexpr std::string_view kSharedFields = R"json({
  "tolerance": {
    "type": "object",
    "additionalProperties": false,
    "properties": {
      "absolute": {
        "type": "number",
        "minimum": 0,
        "description": "allowed |measured - truth|, in the truth's unit"
      },
      "relative": {
        "type": "number",
        "minimum": 0,
        "description": "allowed |measured - truth| / |truth|"
      },
      "reason": {
        "type": "string",
        "description": "why this size: the physics the tolerance allows for (time-step error, slop, solver convergence), shown in the report"
      }
    },
    "description": "required: how far the measurement may be from the truth, with the physical reason for that size; at least one of absolute and relative > 0 (checked by the loader)",
    "required": [
      "reason"
    ]
  },
  "published": {
    "type": "object",
    "additionalProperties": false,
    "required": [
      "value",
      "source"
    ],
    "description": "a figure published for the same case, printed beside the measured one in the report; never judged",
    "properties": {
      "value": {
        "type": "number",
        "description": "the figure, or the low end of a range, in the metric's unit"
      },
      "upper": {
        "type": "number",
        "description": "the high end of a range (>= value); omit for one figure"
      },
      "source": {
        "type": "string",
        "description": "who measured it, with what, e.g. \"Peters & Hsu 2014, ODE and Bullet at 1 ms\""
      }
    }
  },
  "gate": {
    "type": "boolean",
    "description": "default true; false: measured and reported but left out of the CI check (a known shortfall of the engine under test, stated in the scenario's description)"
  },
  "gateReason": {
    "type": "string",
    "description": "required when gate is false (and refused otherwise): why no backend is held to this truth, with the measured figures"
  },
  "ungated": {
    "type": "array",
    "minItems": 0,
    "description": "backends (none when empty, e.g. a sweep value where every backend is gated) for which this truth is a known failure: still measured, judged and reported (FAIL, ungated, with the reason) but not failing talus-testbed check for that backend; the reason gives the physics and the measured figure, never a wider tolerance",
    "items": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "backend",
        "reason"
      ],
      "properties": {
        "backend": {
          "type": "string",
          "description": "registry name, e.g. talus-writeup"
        },
        "reason": {
          "type": "string",
          "description": "why this backend fails the truth, with the measured figure"
        }
      }
    }
  }
})json";

// One kind's form: "kind" naming it, its own fields (the fragment's, in its
// order), then the shared ones; required: "kind", the fragment's, "tolerance".
ordered_json KindForm(std::string_view name, std::string_view fragmentText) {
  static const ordered_json shared = ordered_json::parse(kSharedFields);
  const ordered_json fragment = ordered_json::parse(fragmentText);
  ordered_json required = ordered_json::array({"kind"});
  for (const auto& field : fragment["required"]) required.push_back(field);
  required.push_back("tolerance");
  ordered_json properties;
  properties["kind"] = {{"const", name}};
  for (const auto& [field, form] : fragment["properties"].items()) properties[field] = form;
  for (const auto& [field, form] : shared.items()) properties[field] = form;
  if (fragment.contains("toleranceDescription")) {
    properties["tolerance"]["description"] = fragment["toleranceDescription"];
  }
  ordered_json form;
  form["type"] = "object";
  form["additionalProperties"] = false;
  form["required"] = required;
  form["properties"] = properties;
  return form;
}

}  // namespace

ordered_json TruthFormsSchema() {
  ordered_json forms = ordered_json::array();
  ForEachTruthKind([&](auto tag) {
    using Kind = typename decltype(tag)::type;
    forms.push_back(KindForm(Kind::kName, Kind::Schema()));
  });
  return forms;
}

std::string GeneratedScenarioSchemaText() {
  ordered_json schema = ordered_json::parse(ScenarioSchemaText());
  schema["properties"]["truths"]["items"]["oneOf"] = TruthFormsSchema();
  return schema.dump(2) + "\n";
}

}  // namespace talus::harness
