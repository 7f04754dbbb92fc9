// Scenario files to runs: syntax, schema, sweep expansion, semantic checks.
//
// The order matters for the messages: a syntax error is reported with line
// and column before anything else (scenario_json_text.cpp); the schema then
// guarantees every field has the right type and range, so the mapping
// (scenario_mapping.cpp and the section mappings it calls) may read fields
// without re-checking types and only adds what a schema cannot say (unit
// quaternions, unique names, exactly one of mass and density, truths naming
// existing bodies, no degenerate body: degenerate_body_check.h). Each sweep
// combination is re-validated after its values are written in
// (sweep_expansion.cpp), so a sweep cannot smuggle in a value the schema
// forbids. Folders are walked in scenario_folder_walk.cpp.
#include "talus/harness/scenario/scenario_loader.h"

#include <fstream>
#include <sstream>

#include "scenario/scenario_json_text.h"
#include "scenario/scenario_mapping_support.h"
#include "scenario/scenario_schema_text.h"
#include "scenario/sweep_expansion.h"
#include "support/text_util.h"
#include "talus/harness/support/json_schema.h"

namespace talus::harness {

const nlohmann::json& ScenarioSchema() {
  static const nlohmann::json schema = nlohmann::json::parse(ScenarioSchemaText());
  return schema;
}

namespace {

Result<std::vector<Run>> ParseScenarioDocument(std::string_view text, std::string_view fileName) {
  auto doc = ParseScenarioJson(text, fileName);
  if (!doc) return doc.GetError();
  if (auto violation = ValidateAgainstSchema(ScenarioSchema(), doc.Value())) {
    return FieldError(fileName, violation->pointer, violation->problem);
  }
  return ExpandSweeps(doc.Value(), fileName);
}

}  // namespace

Result<std::vector<Run>> ParseScenarioText(std::string_view text, std::string_view fileName) {
  auto runs = ParseScenarioDocument(text, fileName);
  if (!runs) return Error{TidyMessage(runs.GetError().message)};
  return runs;
}

Result<std::vector<Run>> LoadScenarioFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path.string() + ": cannot open the file"};
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScenarioText(text.str(), path.string());
}

}  // namespace talus::harness
