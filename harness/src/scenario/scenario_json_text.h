// The loader's first step (scenario_loader.h): scenario text to a JSON
// document, before the schema sees it.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "talus/result.h"

namespace talus::harness {

/// The JSON document `text` holds, or an Error naming `fileName` and, for a
/// syntax error, its line and column; a document nested more than
/// kMaxJsonDepth deep is refused.
Result<nlohmann::json> ParseScenarioJson(std::string_view text, std::string_view fileName);

}  // namespace talus::harness
