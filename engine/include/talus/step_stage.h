// The stages of World::Step as data: one enum and one table, in the order
// the step runs them. World::Step walks this table (world_step.cpp),
// StageTimes has one slot per entry (step_statistics.h), the testbed names
// its stage timings from it, and docs/ARCHITECTURE.md and docs/dynamics.md
// list the stages in its order (tests/world/step_stage_test.cpp checks each).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace talus {

/// One stage of World::Step, in the order they run.
enum class Stage {
  UpdateBroadPhase,
  IntegrateVelocities,
  FindContacts,
  PrepareContacts,
  SolveVelocities,
  SolveSplitImpulses,
  ScatterAndStoreImpulses,
  IntegratePositions,
  UpdateSleep,
};

inline constexpr std::size_t kStageCount = 9;

/// What the table says of a stage.
struct StageInfo {
  Stage stage;
  /// The stage's function in world_step.cpp and its name wherever it is
  /// reported (the testbed's stage timings, talus-scenes).
  std::string_view name;
  /// What it does, in one line.
  std::string_view does;
  /// True when, with WorldSettings::threads > 1, its work is split across
  /// the world's job pool (docs/threading.md, "What runs in parallel");
  /// SolveVelocities only with the coloured solver or the soft step (the
  /// scalar sweeps run pair after pair on the calling thread).
  bool workerThreads;
};

/// Every stage, in step order (entry i is Stage i).
inline constexpr std::array<StageInfo, kStageCount> kStages = {{
    {Stage::UpdateBroadPhase, "UpdateBroadPhase",
     "bounding spheres into the broad phase; the only stage that may refuse, so it runs first", true},
    {Stage::IntegrateVelocities, "IntegrateVelocities", "gravity, forces and torques into the velocities",
     true},
    {Stage::FindContacts, "FindContacts",
     "broad-phase pairs; per pair kept, rebuilt or collided; one persistent contact per touching pair", true},
    {Stage::PrepareContacts, "PrepareContacts", "warm-start matching, constraint rows (colours, bundles)",
     true},
    {Stage::SolveVelocities, "SolveVelocities", "warm start, sequential-impulse sweeps", true},
    {Stage::SolveSplitImpulses, "SolveSplitImpulses",
     "split-impulse pseudo-velocities (when selected), timed bounces' position rows", false},
    {Stage::ScatterAndStoreImpulses, "ScatterAndStoreImpulses",
     "solved velocities back to the bodies, each row's impulse into its contact", false},
    {Stage::IntegratePositions, "IntegratePositions", "positions and orientations", true},
    {Stage::UpdateSleep, "UpdateSleep", "islands at rest fall asleep", false},
}};

static_assert(static_cast<std::size_t>(Stage::UpdateSleep) + 1 == kStageCount, "kStageCount counts the enum");

// The table is indexed by the enum: entry i describes Stage i.
constexpr bool StagesInEnumOrder() {
  for (std::size_t i = 0; i < kStageCount; ++i) {
    if (static_cast<std::size_t>(kStages[i].stage) != i) return false;
  }
  return true;
}
static_assert(StagesInEnumOrder(), "kStages lists the stages in enum order");

/// The table's entry for `stage`.
constexpr const StageInfo& StageOf(Stage stage) { return kStages[static_cast<std::size_t>(stage)]; }

}  // namespace talus
