// The two tables at the top of results.json (version 2), which hold once
// what every result would otherwise repeat (docs/testbed-runner.md
// "results.json"; the bytes they save in docs/testbed-report.md "Sizes"):
//
//   "settings": {backend: {"entries": [{"key", "value", "engineDefault"?, "effect"?}],
//                          "lists": [[entry index, ...], ...]}}
//     each backend's distinct settings and its distinct lists of them; a
//     result's "settings" is the index of its list in its backend's "lists".
//     A backend's settings are the same in most of its runs (the time step,
//     iterations and a few scenario-driven values vary), and their texts
//     (engine defaults, the effect of each departure) are long.
//   "metricDefinitions": {run: [{"name", "unit", "tolerance": {"absolute", "relative",
//                                "reason"}, "published"?}]}
//     each run's distinct metric definitions; a result's metric gives the
//     index of its own in its run's list ("definition") beside what was
//     measured. Every backend of a run repeats them, and the tolerances'
//     written reasons are long.
//
// Both tables hold distinct contents, in the order the results first use
// them, so equal results give byte-identical files and every result reads
// back exactly what was written, whatever varies between backends or runs.
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness::results_json {

/// One setting as results.json writes it (in a table or in a full record):
/// key and value; engineDefault and effect only for departures from the
/// engine's defaults. And back; throws ResultsParseFailure naming `where`.
nlohmann::ordered_json SettingToJson(const Setting& setting);
Setting SettingFromJson(const nlohmann::ordered_json& j, const std::string& where);

/// A metric's tolerance ({"absolute", "relative", "reason"}) and published
/// figure ({"value", "upper", "source"}; only metrics of a truth with one
/// carry it, MetricResult::publishedValue not NaN); a non-finite upper end
/// is null unless `exactNumbers` (the wire's CBOR keeps it as it is).
nlohmann::ordered_json ToleranceToJson(const MetricResult& metric);
nlohmann::ordered_json PublishedToJson(const MetricResult& metric, bool exactNumbers);
/// Reads "tolerance" and, when present, "published" of `j` into `metric`.
void ToleranceAndPublishedFromJson(const nlohmann::ordered_json& j, const std::string& where,
                                   MetricResult& metric);

/// The tables built while results are written: each call returns the
/// index a result writes in place of what it would repeat.
class ResultsTableWriter {
 public:
  /// The index of `settings` in `backend`'s lists, added when new.
  std::size_t SettingsList(const std::string& backend, const std::vector<Setting>& settings);
  /// The index of `metric`'s definition (name, unit, tolerance, published)
  /// in `run`'s list, added when new.
  std::size_t MetricDefinition(const std::string& run, const MetricResult& metric);

  /// The "settings" and "metricDefinitions" tables, in first-use order.
  nlohmann::ordered_json SettingsJson() const;
  nlohmann::ordered_json MetricDefinitionsJson() const;

 private:
  struct BackendSettings {
    std::string backend;
    std::vector<nlohmann::ordered_json> entries{};
    std::map<std::string, std::size_t> entryIndex{};  // by the entry's compact text
    std::vector<std::vector<std::size_t>> lists{};
    std::map<std::vector<std::size_t>, std::size_t> listIndex{};
  };
  struct RunDefinitions {
    std::string run;
    std::vector<nlohmann::ordered_json> definitions{};
    std::map<std::string, std::size_t> definitionIndex{};  // by the definition's compact text
  };
  std::vector<BackendSettings> m_settings;
  std::map<std::string, std::size_t> m_settingsIndex;  // by backend
  std::vector<RunDefinitions> m_definitions;
  std::map<std::string, std::size_t> m_definitionsIndex;  // by run
};

/// The tables read back from results.json's top level: every entry checked,
/// every list's indices within its backend's entries.
class ResultsTables {
 public:
  /// Reads "settings" and "metricDefinitions" of `top`; throws
  /// ResultsParseFailure naming the place ("/settings/talus/lists/2/5: ...").
  static ResultsTables Read(const nlohmann::ordered_json& top);

  /// The settings a result of `backend` names with `index` (its "settings"
  /// at `where`); throws naming `where` when `backend` has no table or the
  /// index is not one of its lists.
  const std::vector<Setting>& Settings(const std::string& backend, const nlohmann::ordered_json& index,
                                       const std::string& where) const;
  /// A metric with the name, unit, tolerance, reason and published figure of
  /// the definition a metric of `run` names with `index` (its "definition"
  /// at `where`) and every measured field unset; throws likewise.
  const MetricResult& Definition(const std::string& run, const nlohmann::ordered_json& index,
                                 const std::string& where) const;

 private:
  std::map<std::string, std::vector<std::vector<Setting>>> m_settings;  // by backend
  std::map<std::string, std::vector<MetricResult>> m_definitions;       // by run
};

}  // namespace talus::harness::results_json
