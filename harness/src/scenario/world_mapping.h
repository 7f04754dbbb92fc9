// The loader's mapping of a scenario file's "world" (scenario_loader.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The world settings of a schema-valid "world" object, refusing a gravity,
/// a step count or a duration past scenario_limits.h.
Result<WorldSpec> MapWorld(const nlohmann::json& world, std::string_view file);

}  // namespace talus::harness
