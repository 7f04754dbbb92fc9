// The scenario schema's truths as the table of truth kinds makes them
// (truth_kinds.h): one form per kind, its own fields from the kind's
// Schema() fragment and the fields every truth shares added here. The
// loader validates against the compiled-in scenarios/schema.json; a test
// (tests/harness/truth_kind_table_test.cpp) holds that file to this text.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace talus::harness {

/// The "oneOf" list of the forms a truth entry may take, one per kind in
/// the table's order.
nlohmann::ordered_json TruthFormsSchema();

/// scenarios/schema.json as it must read: the compiled-in schema with its
/// truths' forms replaced by TruthFormsSchema(), two-space indented, with a
/// newline at the end.
std::string GeneratedScenarioSchemaText();

}  // namespace talus::harness
