// The loader's sweep expansion (scenario_loader.h): a scenario document's
// "sweeps" to one run per point of their grid.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The runs of the schema-valid `doc`: one without sweeps, else one per
/// point of the sweeps' grid (first sweep outermost), each id carrying its
/// "name=value" label; targets must name fields outside "sweeps", labels
/// be one per value and unique, perTarget values one entry per target, the
/// grid at most kMaxRuns runs and the ids distinct.
Result<std::vector<Run>> ExpandSweeps(const nlohmann::json& doc, std::string_view fileName);

}  // namespace talus::harness
