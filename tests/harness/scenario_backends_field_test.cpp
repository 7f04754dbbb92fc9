// The scenario file's optional "backends" list: read in file order, empty
// when absent (every backend), and refused when empty, not strings or
// repeated, each with the file and the pointer of the offending entry.
// Unknown names are the runner's to refuse (tests/testbed).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "talus/harness/scenario/scenario_loader.h"

namespace talus::harness {
namespace scenario_backends_field_test {

// A one-body scenario with `backends` as the JSON value of the field, or
// no field when it is empty.
Result<std::vector<Run>> WithBackends(const std::string& backends) {
  const std::string field = backends.empty() ? "" : R"("backends": )" + backends + ",";
  return ParseScenarioText(R"({"name": "x", )" + field +
                               R"( "world": {"timeStep": 0.01, "duration": {"steps": 1}},
          "bodies": [{"name": "b", "shape": {"kind": "sphere", "radius": 1}, "motion": "static",
                      "position": [0, 0, 0]}]})",
                           "x.json");
}

std::string ErrorOf(const std::string& backends) {
  auto runs = WithBackends(backends);
  EXPECT_FALSE(runs) << backends << " was accepted";
  return runs ? std::string() : runs.GetError().message;
}

TEST(ScenarioBackendsField, ListIsReadInFileOrder) {
  auto runs = WithBackends(R"(["ode-step", "talus", "havok"])");
  ASSERT_TRUE(runs) << runs.GetError().message;
  EXPECT_EQ(runs.Value()[0].scenario.backends, (std::vector<std::string>{"ode-step", "talus", "havok"}));
}

TEST(ScenarioBackendsField, AbsentFieldMeansEveryBackend) {
  auto runs = WithBackends("");
  ASSERT_TRUE(runs) << runs.GetError().message;
  EXPECT_TRUE(runs.Value()[0].scenario.backends.empty());
}

TEST(ScenarioBackendsField, DuplicateNameIsRefusedWithItsPointer) {
  const std::string message = ErrorOf(R"(["talus", "bullet", "talus"])");
  EXPECT_NE(message.find("x.json: /backends/2: duplicate backend \"talus\""), std::string::npos) << message;
}

TEST(ScenarioBackendsField, EmptyListIsRefused) {
  const std::string message = ErrorOf("[]");
  EXPECT_NE(message.find("x.json: /backends: needs at least 1 items"), std::string::npos) << message;
}

TEST(ScenarioBackendsField, NonStringEntryIsRefusedWithItsPointer) {
  const std::string message = ErrorOf(R"(["talus", 3])");
  EXPECT_NE(message.find("x.json: /backends/1: must be of type string"), std::string::npos) << message;
}

}  // namespace scenario_backends_field_test
}  // namespace talus::harness
