// The table of truth kinds (truth_kinds.h) is the one place a kind is
// registered: the shipped schema is the table's, every kind's fragment is a
// well-formed piece of it, and names are unique.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/scenario/truth_kinds.h"
#include "talus/harness/scenario/truth_schema.h"

namespace talus::harness {
namespace truth_kind_table_test {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// scenarios/schema.json must be exactly what the table makes; when it is
// not (a kind added or changed), the table's version is written beside
// the test for the author to copy over the file.
TEST(TruthKindTable, ShippedSchemaIsTheTables) {
  const std::string shipped = ReadFile(std::string(TALUS_SCENARIO_DIR) + "/schema.json");
  const std::string generated = GeneratedScenarioSchemaText();
  if (shipped != generated) {
    const std::filesystem::path out = std::filesystem::absolute("schema.generated.json");
    std::ofstream(out, std::ios::binary) << generated;
    FAIL() << "scenarios/schema.json differs from the table of truth kinds; the table's schema is in " << out
           << ": copy it over scenarios/schema.json (and reconfigure)";
  }
}

TEST(TruthKindTable, NamesAreUniqueAndFragmentsWellFormed) {
  std::set<std::string> names;
  ForEachTruthKind([&](auto tag) {
    using Kind = typename decltype(tag)::type;
    const std::string name(Kind::kName);
    EXPECT_TRUE(names.insert(name).second) << name << " is in the table twice";
    const nlohmann::json fragment = nlohmann::json::parse(Kind::Schema());
    ASSERT_TRUE(fragment.contains("properties")) << name;
    ASSERT_TRUE(fragment.contains("required")) << name;
    // Every required field is one the kind describes; none of the shared
    // fields (the loader's) is redefined by a kind.
    for (const auto& field : fragment["required"]) {
      EXPECT_TRUE(fragment["properties"].contains(field.get<std::string>())) << name << ": " << field;
    }
    for (const char* shared : {"kind", "tolerance", "gate", "gateReason", "ungated", "published"}) {
      EXPECT_FALSE(fragment["properties"].contains(shared)) << name << " redefines " << shared;
    }
  });
  EXPECT_EQ(names.size(), std::variant_size_v<TruthKind>);
}

// The forms the schema offers are the table's, in its order.
TEST(TruthKindTable, SchemaFormsFollowTheTable) {
  const auto forms = TruthFormsSchema();
  ASSERT_EQ(forms.size(), std::variant_size_v<TruthKind>);
  std::size_t i = 0;
  ForEachTruthKind([&](auto tag) {
    using Kind = typename decltype(tag)::type;
    EXPECT_EQ(forms[i]["properties"]["kind"]["const"], std::string(Kind::kName));
    EXPECT_EQ(forms[i]["required"].front(), "kind") << Kind::kName;
    ++i;
  });
}

// Every shipped scenario's truths go through their kinds' writers and
// readers: the saved text loads to the same kinds with the same bounds'
// reasons, and saving that again gives the same text (a unit vector the
// reader normalises is settled after one pass).
TEST(TruthKindTable, EveryShippedTruthWritesAndReadsBack) {
  auto runs = LoadScenarios({TALUS_SCENARIO_DIR});
  ASSERT_TRUE(runs) << runs.GetError().message;
  int truths = 0;
  for (const harness::Run& run : runs.Value()) {
    const std::string saved = ScenarioToJson(run.scenario);
    auto again = ParseScenarioText(saved, "saved.json");
    ASSERT_TRUE(again) << run.id << ": " << again.GetError().message;
    const Scenario& reloaded = again.Value().front().scenario;
    ASSERT_EQ(reloaded.truths.size(), run.scenario.truths.size()) << run.id;
    for (std::size_t i = 0; i < reloaded.truths.size(); ++i) {
      EXPECT_EQ(reloaded.truths[i].kind.index(), run.scenario.truths[i].kind.index()) << run.id;
      EXPECT_EQ(reloaded.truths[i].boundReasons, run.scenario.truths[i].boundReasons) << run.id;
      ++truths;
    }
    auto third = ParseScenarioText(ScenarioToJson(reloaded), "saved.json");
    ASSERT_TRUE(third) << run.id;
    EXPECT_EQ(ScenarioToJson(third.Value().front().scenario), ScenarioToJson(reloaded)) << run.id;
  }
  EXPECT_GT(truths, 40);
}

}  // namespace truth_kind_table_test
}  // namespace talus::harness
