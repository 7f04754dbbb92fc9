// The stage table (kStages, talus/step_stage.h) is the one list of
// World::Step's stages: StageTimes has a slot for each, the step times
// each one, and the docs' stage lists name them in the table's order and
// number them 1 to 9 (one numbering everywhere).
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "talus/step_stage.h"
#include "talus/step_statistics.h"
#include "talus/world.h"

namespace talus {
namespace step_stage_test {

std::vector<std::string> TableNames() {
  std::vector<std::string> names;
  for (const StageInfo& stage : kStages) names.emplace_back(stage.name);
  return names;
}

TEST(StepStages, TableNamesEachStageOnceWithAWordOfWhatItDoes) {
  std::set<std::string> seen;
  for (const StageInfo& stage : kStages) {
    EXPECT_TRUE(seen.insert(std::string(stage.name)).second) << stage.name << " is listed twice";
    EXPECT_FALSE(stage.does.empty()) << stage.name;
    EXPECT_EQ(&StageOf(stage.stage), &stage) << stage.name;
  }
  EXPECT_EQ(StageTimes{}.byStage.size(), kStages.size());
}

// With timing on, the stages that do work on a contact scene each take
// some time, every stage's slot is written (>= 0) and the total is the sum
// of the slots in table order.
TEST(StepStages, EveryStageIsTimedUnderItsOwnSlot) {
  World world = World::Create({.timeStages = true}).Value();
  ASSERT_TRUE(world.CreateBody({.type = BodyType::Static, .shape = Shape::CreateBox({5, 0.5, 5}).Value()}));
  ASSERT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {0, 0.69, 0},
                                .shape = Shape::CreateBox({0.2, 0.2, 0.2}).Value()}));
  StepStatistics last;
  for (int n = 0; n < 10; ++n) last = world.Step(1.0 / 60.0).Value();
  double sum = 0.0;
  for (const StageInfo& stage : kStages) {
    EXPECT_GE(last.seconds[stage.stage], 0.0) << stage.name;
    sum += last.seconds[stage.stage];
  }
  EXPECT_EQ(last.seconds.total, sum);
  EXPECT_GT(last.seconds[Stage::FindContacts], 0.0);
  EXPECT_GT(last.seconds[Stage::PrepareContacts], 0.0);
  EXPECT_GT(last.seconds[Stage::SolveVelocities], 0.0);
}

// Each step solver runs the stages of its own table and marks them
// (StageTimes::ran), timed or not: Sequential Impulses all nine, the soft
// step all but the two integrations and the split impulses, which it does
// inside its sub-steps; a stage that did not run has exactly no time.
World BoxOnGround(const WorldSettings& settings) {
  World world = World::Create(settings).Value();
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static, .shape = Shape::CreateBox({5, 0.5, 5}).Value()}));
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Dynamic,
                                .position = {0, 0.69, 0},
                                .shape = Shape::CreateBox({0.2, 0.2, 0.2}).Value()}));
  return world;
}

TEST(StepStages, EachStepSolverMarksTheStagesItRan) {
  for (const bool timed : {false, true}) {
    World sequential = BoxOnGround({.timeStages = timed});
    const StepStatistics si = sequential.Step(1.0 / 60.0).Value();
    for (const StageInfo& stage : kStages)
      EXPECT_TRUE(si.seconds.ran[static_cast<std::size_t>(stage.stage)]) << stage.name;

    WorldSettings softSettings{.timeStages = timed};
    softSettings.methods.stepSolver = StepSolver::SoftStep;
    World soft = BoxOnGround(softSettings);
    const StepStatistics ss = soft.Step(1.0 / 60.0).Value();
    const std::set<Stage> absent = {Stage::IntegrateVelocities, Stage::SolveSplitImpulses,
                                    Stage::IntegratePositions};
    for (const StageInfo& stage : kStages) {
      const bool ran = ss.seconds.ran[static_cast<std::size_t>(stage.stage)];
      EXPECT_EQ(ran, absent.count(stage.stage) == 0) << stage.name;
      if (!ran) {
        EXPECT_EQ(ss.seconds[stage.stage], 0.0) << stage.name;
      }
    }
  }
}

// A line "N. `Name..." as (N, Name); nullopt for any other line. Parsed by
// hand: std::regex trips GCC 12's maybe-uninitialized warning in the
// sanitizer build (-O1), which -Werror turns into an error.
std::optional<std::pair<int, std::string>> NumberedItem(const std::string& line) {
  std::size_t i = 0;
  while (i < line.size() && std::isdigit(static_cast<unsigned char>(line[i])) != 0) ++i;
  if (i == 0 || line.compare(i, 3, ". `") != 0) return std::nullopt;
  std::size_t end = i + 3;
  while (end < line.size() && std::isalpha(static_cast<unsigned char>(line[end])) != 0) ++end;
  if (end == i + 3) return std::nullopt;
  return std::make_pair(std::stoi(line.substr(0, i)), line.substr(i + 3, end - i - 3));
}

// The numbered list of the section under `heading` in a docs file: each
// item "N. `Name..." as (N, Name), up to the next heading.
std::vector<std::pair<int, std::string>> NumberedStages(const std::string& file, const std::string& heading) {
  std::ifstream in(std::string(TALUS_DOCS_DIR) + "/" + file);
  EXPECT_TRUE(in) << "cannot read docs/" << file;
  std::vector<std::pair<int, std::string>> items;
  bool inside = false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind('#', 0) == 0) {
      if (inside) break;
      inside = line == heading;
      continue;
    }
    if (!inside) continue;
    if (const auto item = NumberedItem(line)) items.push_back(*item);
  }
  EXPECT_TRUE(inside || !items.empty()) << "docs/" << file << " has no heading \"" << heading << "\"";
  return items;
}

void ExpectTableOrder(const std::string& file, const std::string& heading) {
  const std::vector<std::pair<int, std::string>> items = NumberedStages(file, heading);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    names.push_back(items[i].second);
    EXPECT_EQ(items[i].first, static_cast<int>(i) + 1)
        << "docs/" << file << ", " << heading << ": " << items[i].second << " should be numbered " << i + 1;
  }
  EXPECT_EQ(names, TableNames()) << "docs/" << file << ", \"" << heading
                                 << "\" lists the stages out of table order";
}

TEST(StepStages, DocsListTheStagesInTableOrder) {
  ExpectTableOrder("ARCHITECTURE.md", "### One step, as data flowing through it");
  ExpectTableOrder("ARCHITECTURE.md", "### One step, stage by stage");
  ExpectTableOrder("dynamics.md", "## The step (`World::Step(dt)`, `world/world_step.cpp`)");
}

}  // namespace step_stage_test
}  // namespace talus
