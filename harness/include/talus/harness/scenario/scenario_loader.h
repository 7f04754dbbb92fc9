// Reading scenario files: JSON syntax, then the schema
// (scenarios/schema.json), then semantic checks, then sweep expansion.
//
// Nothing is half-applied: either every run of the file is returned, each
// fully validated, or one Error whose message starts with the file name and
// names the place, e.g.
//   "scenarios/sliding/box_slide.json: /bodies/1/friction: must be >= 0"
//   "bad.json: line 4, column 7: syntax error ..."
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// The scenario schema (scenarios/schema.json, compiled in), parsed.
const nlohmann::json& ScenarioSchema();

/// Parses scenario text; `fileName` only labels messages. A file without
/// sweeps gives one run; sweeps give the Cartesian product of their values,
/// first sweep outermost, in file order.
Result<std::vector<Run>> ParseScenarioText(std::string_view text, std::string_view fileName);

/// Reads and parses a scenario file (see ParseScenarioText).
Result<std::vector<Run>> LoadScenarioFile(const std::filesystem::path& path);

/// Scenario files from `paths`: files as given, folders searched
/// recursively for *.json except schema.json, each folder's files sorted.
/// Every run of every file, in that order; the first bad file is an Error.
Result<std::vector<Run>> LoadScenarios(const std::vector<std::filesystem::path>& paths);

}  // namespace talus::harness
