// A scenario document's "sweeps" to its runs (sweep_expansion.h): the
// sweeps read and checked, the grid's size bounded before any run is built,
// and each grid point's values written into a copy of the document, which
// is validated again and mapped on its own (a sweep cannot smuggle in a
// value the schema forbids).
#include "scenario/sweep_expansion.h"

#include <optional>
#include <string>
#include <unordered_set>
#include <utility>

#include "scenario/scenario_mapping.h"
#include "scenario/scenario_mapping_support.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/support/json_schema.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// One entry of the file's "sweeps", its targets parsed.
struct ScenarioSweep {
  std::string name;
  std::vector<json::json_pointer> targets;
  std::vector<json> values;
  bool perTarget = false;           // each value holds one entry per target
  std::vector<std::string> labels;  // one per value, or empty
};

// Reads the sweeps and checks that every target names an existing field
// outside the sweeps themselves.
Result<std::vector<ScenarioSweep>> ReadSweeps(const json& doc, std::string_view file) {
  std::vector<ScenarioSweep> sweeps;
  if (!doc.contains("sweeps")) return sweeps;
  for (size_t i = 0; i < doc["sweeps"].size(); ++i) {
    const json& entry = doc["sweeps"][i];
    ScenarioSweep sweep{entry["name"].get<std::string>(),
                        {},
                        entry["values"].get<std::vector<json>>(),
                        entry.value("perTarget", false),
                        {}};
    for (size_t t = 0; t < entry["targets"].size(); ++t) {
      const std::string where = "/sweeps/" + std::to_string(i) + "/targets/" + std::to_string(t);
      const std::string text = entry["targets"][t].get<std::string>();
      try {
        json::json_pointer target(text);
        if (text.rfind("/sweeps", 0) == 0 || !doc.contains(target)) {
          return FieldError(file, where, Quoted(text) + " does not name a field of the scenario");
        }
        sweep.targets.push_back(target);
      } catch (const json::exception&) {
        return FieldError(file, where, Quoted(text) + " is not a JSON pointer");
      }
    }
    if (entry.contains("labels")) {
      sweep.labels = entry["labels"].get<std::vector<std::string>>();
      if (sweep.labels.size() != sweep.values.size()) {
        return FieldError(file, "/sweeps/" + std::to_string(i) + "/labels",
                          "needs one label per value (" + std::to_string(sweep.values.size()) + ")");
      }
      std::unordered_set<std::string> seen;
      for (size_t l = 0; l < sweep.labels.size(); ++l) {
        if (!seen.insert(sweep.labels[l]).second) {
          return FieldError(file, "/sweeps/" + std::to_string(i) + "/labels/" + std::to_string(l),
                            "duplicate label " + Quoted(sweep.labels[l]));
        }
      }
    }
    for (size_t v = 0; sweep.perTarget && v < sweep.values.size(); ++v) {
      if (!sweep.values[v].is_array() || sweep.values[v].size() != sweep.targets.size()) {
        return FieldError(file, "/sweeps/" + std::to_string(i) + "/values/" + std::to_string(v),
                          "a perTarget value must be an array of " + std::to_string(sweep.targets.size()) +
                              " entries, one per target");
      }
    }
    sweeps.push_back(std::move(sweep));
  }
  return sweeps;
}

// The number of runs the sweep grid makes, or nothing when it passes `limit`
// (computed from the sizes, before any run is built).
std::optional<std::size_t> GridSize(const std::vector<ScenarioSweep>& sweeps, std::size_t limit) {
  std::size_t runs = 1;
  for (const ScenarioSweep& sweep : sweeps) {
    if (sweep.values.empty() || runs > limit / sweep.values.size()) return std::nullopt;
    runs *= sweep.values.size();
  }
  return runs;
}

// Refuses a grid of more than kMaxRuns runs, naming its sizes.
std::optional<Error> CheckGridSize(const std::vector<ScenarioSweep>& sweeps, std::string_view fileName) {
  if (GridSize(sweeps, kMaxRuns)) return std::nullopt;
  std::string sizes;
  for (const ScenarioSweep& sweep : sweeps) {
    sizes.append(sizes.empty() ? "" : " x ").append(std::to_string(sweep.values.size()));
  }
  return FieldError(fileName, "/sweeps",
                    Concat({"the grid (", sizes, " values) makes more than the limit of ",
                            std::to_string(kMaxRuns), " runs"}));
}

// Writes the values of grid point `index` (one value index per sweep) into
// `instance` and names them in `run` (sweepValues); the label
// "name=value,..." it returns is empty without sweeps.
std::string ApplyGridPoint(const std::vector<ScenarioSweep>& sweeps, const std::vector<size_t>& index,
                           json& instance, Run& run) {
  std::string label;
  for (size_t s = 0; s < index.size(); ++s) {
    const ScenarioSweep& sweep = sweeps[s];
    const json& value = sweep.values[index[s]];
    for (size_t t = 0; t < sweep.targets.size(); ++t) {
      instance[sweep.targets[t]] = sweep.perTarget ? value[t] : value;
    }
    // A perTarget value is labelled by its first entry (the swept parameter).
    const std::string shown = !sweep.labels.empty() ? sweep.labels[index[s]]
                              : sweep.perTarget     ? value[0].dump()
                                                    : value.dump();
    run.sweepValues.push_back({sweep.name, shown});
    label += (label.empty() ? "" : ",") + sweep.name + "=" + shown;
  }
  return label;
}

// The run of grid point `index`: the document with its values written in,
// validated again and mapped; messages name the point after the file.
Result<Run> MakeGridPointRun(const json& doc, const std::vector<ScenarioSweep>& sweeps,
                             const std::vector<size_t>& index, std::string_view fileName) {
  json instance = doc;
  instance.erase("sweeps");
  Run run;
  run.id = doc["name"].get<std::string>();
  const std::string label = ApplyGridPoint(sweeps, index, instance, run);
  if (!label.empty()) run.id += "[" + label + "]";
  const std::string where =
      label.empty() ? std::string(fileName) : std::string(fileName) + " (" + label + ")";
  if (auto violation = ValidateAgainstSchema(ScenarioSchema(), instance)) {
    return FieldError(where, violation->pointer, violation->problem);
  }
  auto scenario = MapScenario(instance, where);
  if (!scenario) return scenario.GetError();
  run.scenario = std::move(scenario).Value();
  run.scenario.file = std::string(fileName);
  run.timeStep = run.scenario.world.timeStep;
  run.iterations = run.scenario.world.iterations;
  run.steps = run.scenario.world.steps;
  return run;
}

// Moves `index` to the next grid point, the last sweep fastest (an
// odometer); false once every point has been visited.
bool NextGridPoint(const std::vector<ScenarioSweep>& sweeps, std::vector<size_t>& index) {
  size_t s = index.size();
  while (s > 0 && ++index[s - 1] == sweeps[s - 1].values.size()) index[--s] = 0;
  return s != 0;
}

}  // namespace

Result<std::vector<Run>> ExpandSweeps(const json& doc, std::string_view fileName) {
  auto sweeps = ReadSweeps(doc, fileName);
  if (!sweeps) return sweeps.GetError();
  if (auto problem = CheckGridSize(sweeps.Value(), fileName)) return *problem;
  std::unordered_set<std::string> runIds;
  std::vector<size_t> index(sweeps.Value().size(), 0);
  std::vector<Run> runs;
  do {
    auto run = MakeGridPointRun(doc, sweeps.Value(), index, fileName);
    if (!run) return run.GetError();
    if (!runIds.insert(run.Value().id).second) {
      return FieldError(fileName, "/sweeps",
                        Concat({"two runs are both named ", Quoted(run.Value().id),
                                " (a sweep repeats a value or label)"}));
    }
    runs.push_back(std::move(run).Value());
  } while (NextGridPoint(sweeps.Value(), index));
  return runs;
}

}  // namespace talus::harness
