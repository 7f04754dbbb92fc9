// The settings and metric-definition tables of results.json (see
// results_tables.h): built in first-use order while the results are
// written, read back and checked before any result refers to them.
#include "run/results_tables.h"

#include <cmath>
#include <utility>

#include "run/results_json_walk.h"
#include "support/text_util.h"

namespace talus::harness::results_json {
namespace {

// The position `index` (a result's reference at `where`) names in a table
// of `size` entries, `what` saying whose table it is.
std::size_t Reference(const Json& index, std::size_t size, const std::string& where,
                      const std::string& what) {
  if (!index.is_number_integer()) throw ResultsParseFailure{Concat({where, ": expected an integer index"})};
  const long long value = index.get<long long>();
  if (value < 0 || static_cast<unsigned long long>(value) >= size) {
    throw ResultsParseFailure{
        Concat({where, ": ", index.dump(), " is not an index of the ", std::to_string(size), " ", what})};
  }
  return static_cast<std::size_t>(value);
}

// The index of `value` in `values`, appended when new; `index` maps each
// value's key to its position.
template <typename Key, typename Value>
std::size_t Intern(const Key& key, Value&& value, std::vector<std::decay_t<Value>>& values,
                   std::map<Key, std::size_t>& index) {
  const auto [it, added] = index.try_emplace(key, values.size());
  if (added) values.push_back(std::forward<Value>(value));
  return it->second;
}

Json DefinitionToJson(const MetricResult& m) {
  Json j;
  j["name"] = m.name;
  j["unit"] = m.unit;
  j["tolerance"] = ToleranceToJson(m);
  if (!std::isnan(m.publishedValue)) j["published"] = PublishedToJson(m, false);
  return j;
}

std::vector<std::vector<Setting>> ReadBackendSettings(const Json& table, const std::string& where) {
  const Json& entries = GetArray(table, "entries", where);
  std::vector<Setting> settings;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    settings.push_back(SettingFromJson(entries[i], Concat({where, "/entries/", std::to_string(i)})));
  }
  const Json& lists = GetArray(table, "lists", where);
  std::vector<std::vector<Setting>> read;
  for (std::size_t i = 0; i < lists.size(); ++i) {
    const std::string at = Concat({where, "/lists/", std::to_string(i)});
    if (!lists[i].is_array()) throw ResultsParseFailure{Concat({at, ": expected an array of entry indices"})};
    std::vector<Setting>& list = read.emplace_back();
    for (std::size_t k = 0; k < lists[i].size(); ++k) {
      list.push_back(settings[Reference(lists[i][k], settings.size(), Concat({at, "/", std::to_string(k)}),
                                        "entries of this backend")]);
    }
  }
  return read;
}

}  // namespace

Json SettingToJson(const Setting& s) {
  Json setting = {{"key", s.key}, {"value", s.value}};
  // Only departures from the engine's defaults carry these two.
  if (!s.engineDefault.empty()) setting["engineDefault"] = s.engineDefault;
  if (!s.effect.empty()) setting["effect"] = s.effect;
  return setting;
}

Setting SettingFromJson(const Json& j, const std::string& where) {
  Setting setting{GetString(j, "key", where), GetString(j, "value", where)};
  if (j.contains("engineDefault")) setting.engineDefault = GetString(j, "engineDefault", where);
  if (j.contains("effect")) setting.effect = GetString(j, "effect", where);
  return setting;
}

Json ToleranceToJson(const MetricResult& m) {
  return {{"absolute", m.tolerance.absolute}, {"relative", m.tolerance.relative}, {"reason", m.reason}};
}

Json PublishedToJson(const MetricResult& m, bool exactNumbers) {
  // A figure without an upper end has NaN there: null, as every NaN.
  const bool asIs = std::isfinite(m.publishedUpper) || exactNumbers;
  return {{"value", m.publishedValue},
          {"upper", asIs ? Json(m.publishedUpper) : Json(nullptr)},
          {"source", m.publishedSource}};
}

void ToleranceAndPublishedFromJson(const Json& j, const std::string& where, MetricResult& m) {
  const Json& tolerance = Field(j, "tolerance", where);
  const std::string at = Place(where, "tolerance");
  m.tolerance.absolute = GetNumber(tolerance, "absolute", at);
  m.tolerance.relative = GetNumber(tolerance, "relative", at);
  m.reason = GetString(tolerance, "reason", at);
  if (j.contains("published")) {
    const Json& published = Field(j, "published", where);
    const std::string place = Place(where, "published");
    m.publishedValue = GetNumber(published, "value", place);
    m.publishedUpper = GetNumber(published, "upper", place);
    m.publishedSource = GetString(published, "source", place);
  }
}

std::size_t ResultsTableWriter::SettingsList(const std::string& backend,
                                             const std::vector<Setting>& settings) {
  BackendSettings& table = m_settings[Intern(backend, BackendSettings{backend}, m_settings, m_settingsIndex)];
  std::vector<std::size_t> list;
  for (const Setting& setting : settings) {
    Json entry = SettingToJson(setting);
    const std::string key = entry.dump();
    list.push_back(Intern(key, std::move(entry), table.entries, table.entryIndex));
  }
  const std::vector<std::size_t> key = list;
  return Intern(key, std::move(list), table.lists, table.listIndex);
}

std::size_t ResultsTableWriter::MetricDefinition(const std::string& run, const MetricResult& metric) {
  RunDefinitions& table = m_definitions[Intern(run, RunDefinitions{run}, m_definitions, m_definitionsIndex)];
  Json definition = DefinitionToJson(metric);
  const std::string key = definition.dump();
  return Intern(key, std::move(definition), table.definitions, table.definitionIndex);
}

Json ResultsTableWriter::SettingsJson() const {
  Json j = Json::object();
  for (const BackendSettings& table : m_settings) {
    j[table.backend] = {{"entries", table.entries}, {"lists", table.lists}};
  }
  return j;
}

Json ResultsTableWriter::MetricDefinitionsJson() const {
  Json j = Json::object();
  for (const RunDefinitions& table : m_definitions) j[table.run] = table.definitions;
  return j;
}

ResultsTables ResultsTables::Read(const Json& top) {
  ResultsTables tables;
  const Json& settings = Field(top, "settings", "");
  if (!settings.is_object()) throw ResultsParseFailure{"/settings: expected an object of backends' tables"};
  for (const auto& [backend, table] : settings.items()) {
    tables.m_settings[backend] = ReadBackendSettings(table, Concat({"/settings/", backend}));
  }
  const Json& definitions = Field(top, "metricDefinitions", "");
  if (!definitions.is_object())
    throw ResultsParseFailure{"/metricDefinitions: expected an object of runs' lists"};
  for (const auto& [run, list] : definitions.items()) {
    const std::string where = Concat({"/metricDefinitions/", run});
    if (!list.is_array()) throw ResultsParseFailure{Concat({where, ": expected an array"})};
    std::vector<MetricResult>& read = tables.m_definitions[run];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = Concat({where, "/", std::to_string(i)});
      MetricResult& m =
          read.emplace_back(MakeMetric(GetString(list[i], "name", at), GetString(list[i], "unit", at)));
      ToleranceAndPublishedFromJson(list[i], at, m);
    }
  }
  return tables;
}

const std::vector<Setting>& ResultsTables::Settings(const std::string& backend, const Json& index,
                                                    const std::string& where) const {
  const auto it = m_settings.find(backend);
  if (it == m_settings.end()) {
    throw ResultsParseFailure{Concat({where, ": backend \"", backend, "\" has no table in /settings"})};
  }
  return it
      ->second[Reference(index, it->second.size(), where, Concat({"settings lists of \"", backend, "\""}))];
}

const MetricResult& ResultsTables::Definition(const std::string& run, const Json& index,
                                              const std::string& where) const {
  const auto it = m_definitions.find(run);
  if (it == m_definitions.end()) {
    throw ResultsParseFailure{Concat({where, ": run \"", run, "\" has no list in /metricDefinitions"})};
  }
  return it
      ->second[Reference(index, it->second.size(), where, Concat({"metric definitions of \"", run, "\""}))];
}

}  // namespace talus::harness::results_json
