// The loader's mapping of a schema-valid scenario document (one sweep point,
// its values written in) to the scenario model (scenario_loader.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The scenario `doc` describes, adding the semantic checks a schema cannot
/// make (finite numbers, limits, unique names, truths naming existing
/// bodies, ...); the first refusal names `file` and the field.
Result<Scenario> MapScenario(const nlohmann::json& doc, std::string_view file);

}  // namespace talus::harness
