// The loader's mapping of one entry of a scenario file's "truths"
// (scenario_loader.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "scenario/scenario_mapping_support.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The truth of a schema-valid entry at `pointer` ("/truths/<i>") of a
/// scenario whose bodies and world are already read: its "body" must name
/// one of `bodies`; its kind's fields are read by the kind's unit; the
/// tolerance must allow something and say where it comes from; the gate,
/// "ungated" (each backend once, with its reason), every secondary bound's
/// reason, "gateReason" (given exactly when the truth is not gated) and
/// "published" are checked.
Result<Truth> MapTruth(const nlohmann::json& entry, const std::vector<BodySpec>& bodies,
                       const BodyIndex& names, const WorldSpec& world, std::string_view file,
                       const std::string& pointer);

}  // namespace talus::harness
