// A validator for the small JSON-Schema subset the scenario schema uses.
//
// Debian packages no C++ JSON-Schema validator, so the schema
// (scenarios/schema.json) is written once as data and checked by this code.
// Supported keywords: type (object, array, string, number, integer, boolean),
// required, properties, additionalProperties (false only), enum, const,
// minimum, maximum, exclusiveMinimum, exclusiveMaximum (numbers), items (one
// schema for every element), minItems, maxItems and oneOf. "description",
// "title" and "$schema" are annotations and ignored. Any other keyword in a
// schema is a programmer error (asserted), so the schema cannot silently use
// a rule that is not enforced.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace talus::harness {

/// Where and why an instance breaks its schema.
struct SchemaViolation {
  std::string pointer;  ///< JSON pointer of the offending value, e.g. "/bodies/2/friction" ("" = root)
  std::string problem;  ///< what is wrong, e.g. "unknown field", "must be >= 0"
};

/// Checks `instance` against `schema`; the first violation in document order,
/// or nothing when it conforms. For oneOf, when the value is an object whose
/// field matches a branch's "const" property (a discriminator such as
/// "kind": "box"), that branch's own violation is reported, so messages name
/// the real field instead of "matches no alternative".
std::optional<SchemaViolation> ValidateAgainstSchema(const nlohmann::json& schema,
                                                     const nlohmann::json& instance);

}  // namespace talus::harness
