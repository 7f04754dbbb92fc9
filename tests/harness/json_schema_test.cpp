// The JSON-Schema subset validator, keyword by keyword.
#include <gtest/gtest.h>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/support/json_schema.h"

namespace talus::harness {
namespace json_schema_test {

using nlohmann::json;

std::string Check(const json& schema, const json& value) {
  auto violation = ValidateAgainstSchema(schema, value);
  return violation ? violation->pointer + ": " + violation->problem : "ok";
}

TEST(JsonSchema, TypesAreCheckedAndIntegerRefusesFractions) {
  EXPECT_EQ(Check({{"type", "integer"}}, 3), "ok");
  EXPECT_EQ(Check({{"type", "integer"}}, 3.0), "ok");
  EXPECT_EQ(Check({{"type", "integer"}}, 3.5), ": must be of type integer, not number");
  EXPECT_EQ(Check({{"type", "string"}}, true), ": must be of type string, not boolean");
}

TEST(JsonSchema, BoundsAreInclusiveOrExclusiveAsWritten) {
  const json schema = {{"type", "number"}, {"minimum", 0}, {"exclusiveMaximum", 1}};
  EXPECT_EQ(Check(schema, 0), "ok");
  EXPECT_EQ(Check(schema, -0.5), ": must be >= 0");
  EXPECT_EQ(Check(schema, 1), ": must be < 1");
}

TEST(JsonSchema, ObjectsReportMissingAndUnknownFieldsWithPointers) {
  const json schema = json::parse(R"({"type": "object", "additionalProperties": false, "required": ["a"],
      "properties": {"a": {"type": "array", "minItems": 1, "maxItems": 2, "items": {"enum": ["x", "y"]}},
                     "b/c": {"type": "number"}}})");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": ["x"]})")), "ok");
  EXPECT_EQ(Check(schema, json::parse(R"({})")), ": missing required field \"a\"");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": ["x"], "z": 1})")), "/z: unknown field");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": ["x", "q"]})")), "/a/1: must be one of [\"x\",\"y\"]");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": []})")), "/a: needs at least 1 items");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": ["x", "x", "y"]})")), "/a: allows at most 2 items");
  EXPECT_EQ(Check(schema, json::parse(R"({"a": ["x"], "b/c": "s"})")),
            "/b~1c: must be of type number, not string");
}

TEST(JsonSchema, OneOfNeedsExactlyOneMatchAndFollowsTheDiscriminator) {
  const json schema = json::parse(R"({"oneOf": [
      {"type": "object", "additionalProperties": false, "required": ["kind", "r"],
       "properties": {"kind": {"const": "s"}, "r": {"type": "number", "exclusiveMinimum": 0}}},
      {"type": "object", "additionalProperties": false, "required": ["kind"],
       "properties": {"kind": {"const": "p"}}}]})");
  EXPECT_EQ(Check(schema, json::parse(R"({"kind": "s", "r": 1})")), "ok");
  EXPECT_EQ(Check(schema, json::parse(R"({"kind": "s", "r": 0})")), "/r: must be > 0");
  EXPECT_EQ(Check(schema, json::parse(R"({"kind": "q"})")),
            ": matches none of the allowed forms (see scenarios/schema.json)");
  EXPECT_EQ(Check({{"oneOf", {json::object(), json::object()}}}, 1),
            ": matches more than one of the allowed forms");
}

TEST(JsonSchema, ScenarioSchemaIsAnObjectSchemaClosedToUnknownFields) {
  const json& schema = ScenarioSchema();
  EXPECT_EQ(schema["type"], "object");
  EXPECT_EQ(schema["additionalProperties"], false);
  EXPECT_EQ(Check(schema, json::parse(R"({"name": "x"})")), ": missing required field \"world\"");
}

}  // namespace json_schema_test
}  // namespace talus::harness
