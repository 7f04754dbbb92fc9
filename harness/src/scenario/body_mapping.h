// The loader's mapping of one body of a scenario file's "bodies"
// (scenario_loader.h): shape, motion, pose, velocities, mass, material.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The body of a schema-valid entry at `pointer` ("/bodies/<i>"), with the
/// checks a schema cannot make: a unit quaternion or a non-zero axis,
/// exactly one of mass and density for a dynamic body (neither otherwise),
/// no velocities on a static body, sizes, positions and speeds within
/// scenario_limits.h, and no degenerate body (degenerate_body_check.h).
Result<BodySpec> MapBody(const nlohmann::json& body, std::string_view file, const std::string& pointer);

}  // namespace talus::harness
