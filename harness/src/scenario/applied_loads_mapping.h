// The loader's mapping of a scenario file's "loads" and "impulses"
// (scenario_loader.h): each names a dynamic body and acts inside the run.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "scenario/scenario_mapping_support.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The document's "loads" (none when it has none): each names a dynamic
/// body, has a force or a torque, a point only with a force, and a window
/// inside the run `world` gives.
Result<std::vector<AppliedLoad>> MapLoads(const nlohmann::json& doc, const std::vector<BodySpec>& bodies,
                                          const BodyIndex& names, const WorldSpec& world,
                                          std::string_view file);

/// The document's "impulses" (none when it has none): each names a dynamic
/// body and a time before the run's last step.
Result<std::vector<AppliedImpulse>> MapImpulses(const nlohmann::json& doc,
                                                const std::vector<BodySpec>& bodies, const BodyIndex& names,
                                                const WorldSpec& world, std::string_view file);

}  // namespace talus::harness
