// The text of scenarios/schema.json, compiled in by CMake (see
// harness/CMakeLists.txt), so that the schema is written once, as data, and
// the library validates against exactly the file that is documented.
#pragma once

#include <string_view>

namespace talus::harness {

/// The scenario JSON schema, verbatim.
std::string_view ScenarioSchemaText();

}  // namespace talus::harness
