// The JSON-Schema subset validator (see talus/harness/support/json_schema.h).
//
// A recursive walk of schema and instance together, carrying the instance's
// JSON pointer. Objects are checked in a fixed order (type, required,
// unknown fields, then each property in key order; nlohmann::json keeps
// object keys sorted) so the reported
// violation is deterministic. Semantics follow JSON Schema 2020-12 for the
// keywords supported; "integer" accepts any number with no fractional part.
#include "talus/harness/support/json_schema.h"

#include <cassert>
#include <cmath>
#include <string>

#include "talus/harness/support/number_text.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// Escapes a field name for a JSON pointer (RFC 6901: ~ -> ~0, / -> ~1).
std::string EscapePointerToken(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

[[maybe_unused]] bool IsKnownKeyword(const std::string& key) {
  static const char* const kKeywords[] = {"type",
                                          "required",
                                          "properties",
                                          "additionalProperties",
                                          "enum",
                                          "const",
                                          "minimum",
                                          "maximum",
                                          "exclusiveMinimum",
                                          "exclusiveMaximum",
                                          "items",
                                          "minItems",
                                          "maxItems",
                                          "oneOf",
                                          "description",
                                          "title",
                                          "$schema"};
  for (const char* keyword : kKeywords) {
    if (key == keyword) return true;
  }
  return false;
}

// The instance's type in schema words, "integer" reported as "number".
const char* TypeName(const json& value) {
  switch (value.type()) {
    case json::value_t::object:
      return "object";
    case json::value_t::array:
      return "array";
    case json::value_t::string:
      return "string";
    case json::value_t::boolean:
      return "boolean";
    case json::value_t::null:
      return "null";
    default:
      return "number";
  }
}

bool MatchesType(const json& value, const std::string& type) {
  if (type == "object") return value.is_object();
  if (type == "array") return value.is_array();
  if (type == "string") return value.is_string();
  if (type == "boolean") return value.is_boolean();
  if (type == "number") return value.is_number();
  if (type == "integer") {
    if (value.is_number_integer()) return true;
    if (!value.is_number_float()) return false;
    const double d = value.get<double>();
    return std::isfinite(d) && std::floor(d) == d;
  }
  assert(false && "unsupported schema type");
  return false;
}

std::optional<SchemaViolation> Validate(const json& schema, const json& value, const std::string& pointer);

std::optional<SchemaViolation> ValidateNumber(const json& schema, const json& value,
                                              const std::string& pointer) {
  if (!value.is_number()) return std::nullopt;
  const double x = value.get<double>();
  if (!std::isfinite(x)) return SchemaViolation{pointer, "must be a finite number"};
  if (schema.contains("minimum") && x < schema["minimum"].get<double>()) {
    return SchemaViolation{pointer, "must be >= " + FormatNumber(schema["minimum"].get<double>())};
  }
  if (schema.contains("exclusiveMinimum") && x <= schema["exclusiveMinimum"].get<double>()) {
    return SchemaViolation{pointer, "must be > " + FormatNumber(schema["exclusiveMinimum"].get<double>())};
  }
  if (schema.contains("maximum") && x > schema["maximum"].get<double>()) {
    return SchemaViolation{pointer, "must be <= " + FormatNumber(schema["maximum"].get<double>())};
  }
  if (schema.contains("exclusiveMaximum") && x >= schema["exclusiveMaximum"].get<double>()) {
    return SchemaViolation{pointer, "must be < " + FormatNumber(schema["exclusiveMaximum"].get<double>())};
  }
  return std::nullopt;
}

std::optional<SchemaViolation> ValidateObject(const json& schema, const json& value,
                                              const std::string& pointer) {
  if (!value.is_object()) return std::nullopt;
  if (schema.contains("required")) {
    for (const json& name : schema["required"]) {
      if (!value.contains(name.get<std::string>())) {
        return SchemaViolation{pointer, "missing required field \"" + name.get<std::string>() + "\""};
      }
    }
  }
  const json* properties = schema.contains("properties") ? &schema["properties"] : nullptr;
  if (schema.contains("additionalProperties")) {
    assert(schema["additionalProperties"] == false && "only additionalProperties: false is supported");
    // nlohmann's object iterates keys in sorted order: deterministic.
    for (const auto& [key, unused] : value.items()) {
      if (properties == nullptr || !properties->contains(key)) {
        return SchemaViolation{pointer + "/" + EscapePointerToken(key), "unknown field"};
      }
    }
  }
  if (properties != nullptr) {
    for (const auto& [key, subschema] : properties->items()) {
      if (!value.contains(key)) continue;
      if (auto violation = Validate(subschema, value[key], pointer + "/" + EscapePointerToken(key))) {
        return violation;
      }
    }
  }
  return std::nullopt;
}

std::optional<SchemaViolation> ValidateArray(const json& schema, const json& value,
                                             const std::string& pointer) {
  if (!value.is_array()) return std::nullopt;
  if (schema.contains("minItems") && value.size() < schema["minItems"].get<size_t>()) {
    return SchemaViolation{pointer,
                           "needs at least " + std::to_string(schema["minItems"].get<size_t>()) + " items"};
  }
  if (schema.contains("maxItems") && value.size() > schema["maxItems"].get<size_t>()) {
    return SchemaViolation{pointer,
                           "allows at most " + std::to_string(schema["maxItems"].get<size_t>()) + " items"};
  }
  if (schema.contains("items")) {
    for (size_t i = 0; i < value.size(); ++i) {
      if (auto violation = Validate(schema["items"], value[i], pointer + "/" + std::to_string(i)))
        return violation;
    }
  }
  return std::nullopt;
}

// Whether `branch` is the alternative `value` declares itself to be: some
// property of the branch has a "const" that the value's field equals.
bool DiscriminatorMatches(const json& branch, const json& value) {
  if (!value.is_object() || !branch.contains("properties")) return false;
  for (const auto& [key, subschema] : branch["properties"].items()) {
    if (subschema.contains("const") && value.contains(key) && value[key] == subschema["const"]) return true;
  }
  return false;
}

std::optional<SchemaViolation> ValidateOneOf(const json& schema, const json& value,
                                             const std::string& pointer) {
  if (!schema.contains("oneOf")) return std::nullopt;
  int matches = 0;
  std::optional<SchemaViolation> chosen;
  for (const json& branch : schema["oneOf"]) {
    auto violation = Validate(branch, value, pointer);
    if (!violation) {
      ++matches;
    } else if (DiscriminatorMatches(branch, value)) {
      chosen = violation;
    }
  }
  if (matches == 1) return std::nullopt;
  if (matches > 1) return SchemaViolation{pointer, "matches more than one of the allowed forms"};
  if (chosen) return chosen;
  return SchemaViolation{pointer, "matches none of the allowed forms (see scenarios/schema.json)"};
}

std::optional<SchemaViolation> Validate(const json& schema, const json& value, const std::string& pointer) {
  assert(schema.is_object());
  for (const auto& [key, unused] : schema.items()) {
    assert(IsKnownKeyword(key) && "schema uses a keyword the validator does not enforce");
    (void)key;
  }
  if (schema.contains("type") && !MatchesType(value, schema["type"].get<std::string>())) {
    return SchemaViolation{
        pointer, "must be of type " + schema["type"].get<std::string>() + ", not " + TypeName(value)};
  }
  if (schema.contains("const") && value != schema["const"]) {
    return SchemaViolation{pointer, "must be " + schema["const"].dump()};
  }
  if (schema.contains("enum")) {
    bool found = false;
    for (const json& allowed : schema["enum"]) found = found || value == allowed;
    if (!found) return SchemaViolation{pointer, "must be one of " + schema["enum"].dump()};
  }
  if (auto violation = ValidateNumber(schema, value, pointer)) return violation;
  if (auto violation = ValidateObject(schema, value, pointer)) return violation;
  if (auto violation = ValidateArray(schema, value, pointer)) return violation;
  return ValidateOneOf(schema, value, pointer);
}

}  // namespace

std::optional<SchemaViolation> ValidateAgainstSchema(const nlohmann::json& schema,
                                                     const nlohmann::json& instance) {
  return Validate(schema, instance, "");
}

}  // namespace talus::harness
