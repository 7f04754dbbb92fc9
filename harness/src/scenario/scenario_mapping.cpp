// A schema-valid scenario document to the scenario model, with the checks
// a schema cannot make (scenario_mapping.h). Each section has its own
// mapping: world_mapping, body_mapping, applied_loads_mapping,
// truth_entry_mapping.
#include "scenario/scenario_mapping.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "scenario/applied_loads_mapping.h"
#include "scenario/body_mapping.h"
#include "scenario/scenario_mapping_support.h"
#include "scenario/scenario_names.h"
#include "scenario/truth_entry_mapping.h"
#include "scenario/world_mapping.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// Every number in the document must be finite (JSON text such as 1e999
// parses to infinity); the first offending pointer is named.
std::optional<std::string> FindNonFinite(const json& value, const std::string& pointer) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) return pointer;
  if (value.is_array()) {
    for (size_t i = 0; i < value.size(); ++i) {
      if (auto found = FindNonFinite(value[i], pointer + "/" + std::to_string(i))) return found;
    }
  } else if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      if (auto found = FindNonFinite(child, pointer + "/" + key)) return found;
    }
  }
  return std::nullopt;
}

// The document's "bodies", each name once, indexed by name into `names`.
std::optional<Error> MapBodies(const json& doc, std::string_view file, Scenario& scenario, BodyIndex& names) {
  for (size_t i = 0; i < doc["bodies"].size(); ++i) {
    const std::string pointer = "/bodies/" + std::to_string(i);
    auto body = MapBody(doc["bodies"][i], file, pointer);
    if (!body) return body.GetError();
    if (!names.emplace(body.Value().name, static_cast<int>(i)).second) {
      return FieldError(file, pointer + "/name", "duplicate body name " + Quoted(body.Value().name));
    }
    scenario.bodies.push_back(std::move(body).Value());
  }
  return std::nullopt;
}

// The document's "backends" (each once) and "measure".
std::optional<Error> MapBackendsAndMeasures(const json& doc, std::string_view file, Scenario& scenario) {
  if (doc.contains("backends")) {
    for (size_t i = 0; i < doc["backends"].size(); ++i) {
      const std::string name = doc["backends"][i].get<std::string>();
      if (std::find(scenario.backends.begin(), scenario.backends.end(), name) != scenario.backends.end()) {
        return FieldError(file, "/backends/" + std::to_string(i), "duplicate backend " + Quoted(name));
      }
      scenario.backends.push_back(name);
    }
  }
  if (doc.contains("measure")) {
    for (const json& name : doc["measure"])
      scenario.measure.push_back(QuantityNamed(name.get<std::string>()));
  }
  return std::nullopt;
}

// The document's "truths", read after the bodies and the world they name.
std::optional<Error> MapTruths(const json& doc, std::string_view file, const BodyIndex& names,
                               Scenario& scenario) {
  if (!doc.contains("truths")) return std::nullopt;
  for (size_t i = 0; i < doc["truths"].size(); ++i) {
    auto truth = MapTruth(doc["truths"][i], scenario.bodies, names, scenario.world, file,
                          "/truths/" + std::to_string(i));
    if (!truth) return truth.GetError();
    scenario.truths.push_back(std::move(truth).Value());
  }
  return std::nullopt;
}

}  // namespace

Result<Scenario> MapScenario(const json& doc, std::string_view file) {
  if (auto pointer = FindNonFinite(doc, "")) return FieldError(file, *pointer, "must be a finite number");
  Scenario scenario;
  scenario.name = doc["name"].get<std::string>();
  scenario.description = doc.value("description", "");
  scenario.file = std::string(file);
  auto world = MapWorld(doc["world"], file);
  if (!world) return world.GetError();
  scenario.world = world.Value();
  BodyIndex names;  // linear in the body count (100,000 bodies load at once)
  if (auto problem = MapBodies(doc, file, scenario, names)) return *problem;
  auto loads = MapLoads(doc, scenario.bodies, names, scenario.world, file);
  if (!loads) return loads.GetError();
  scenario.loads = std::move(loads).Value();
  auto impulses = MapImpulses(doc, scenario.bodies, names, scenario.world, file);
  if (!impulses) return impulses.GetError();
  scenario.impulses = std::move(impulses).Value();
  if (auto problem = MapBackendsAndMeasures(doc, file, scenario)) return *problem;
  if (auto problem = MapTruths(doc, file, names, scenario)) return *problem;
  return scenario;
}

}  // namespace talus::harness
