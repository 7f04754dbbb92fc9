// StepStatistics: what one World::Step did and what it skipped. The engine
// promises to spend nothing on what a scene does not use; these counters are
// how the testbed (and the tests) check that promise. Times are wall-clock
// and vary run to run; every count is deterministic.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "talus/broad_phase.h"
#include "talus/narrow_phase.h"
#include "talus/step_stage.h"

namespace talus {

/// Wall-clock seconds spent in each stage of one step, one slot per entry
/// of the stage table (kStages, step_stage.h), read and written by Stage;
/// the stages partition the step, so `total` is their sum. All 0 unless
/// WorldSettings::timeStages is on.
struct StageTimes {
  std::array<double, kStageCount> byStage = {};  ///< seconds of each stage, in kStages order
  /// Whether the step's solver ran each stage, in kStages order: the soft
  /// step has no integration or split-impulse stage of its own, so those
  /// stay false (and their seconds 0) under it. Set whether or not
  /// stages are timed.
  std::array<bool, kStageCount> ran = {};
  double total = 0.0;  ///< the whole step

  double& operator[](Stage stage) { return byStage[static_cast<std::size_t>(stage)]; }
  double operator[](Stage stage) const { return byStage[static_cast<std::size_t>(stage)]; }
};

/// Every count is a std::int64_t, here and in BroadPhaseStats and
/// NarrowPhaseStats, and each name means one thing across the three:
/// candidatePairs (broad phase) are pairs before the sphere test,
/// spherePairs the pairs after it; contactPoints are the normal rows solved,
/// NarrowPhaseStats::manifoldPoints the points the narrow phase produced.
struct StepStatistics {
  StageTimes seconds = {};
  std::int64_t bodies = 0;                ///< live bodies
  std::int64_t awakeBodies = 0;           ///< dynamic bodies integrated this step
  std::int64_t sleepingBodies = 0;        ///< dynamic bodies skipped because asleep
  std::int64_t spherePairs = 0;           ///< pairs the broad phase passed on (= broadPhase.spherePairs)
  std::int64_t staticPairsSkipped = 0;    ///< pairs of two non-dynamic bodies never tested
  std::int64_t sleepingPairsSkipped = 0;  ///< pairs kept from last step because both sides sleep
  std::int64_t manifolds = 0;             ///< touching pairs handed to the solver
  std::int64_t manifoldsReused = 0;       ///< of those, rebuilt without the narrow phase (reuseDistance)
  std::int64_t reusedContactPoints = 0;   ///< points of the reused manifolds
  std::int64_t persistentPoints = 0;      ///< remembered points added to fresh manifolds (persistence)
  std::int64_t contactPoints = 0;         ///< normal rows solved
  std::int64_t frictionRows = 0;          ///< tangent rows solved (two per point with mu > 0)
  std::int64_t frictionRowsSkipped = 0;   ///< tangent rows not built because mu = 0
  std::int64_t restitutionSkipped = 0;    ///< points whose restitution work was skipped (e = 0)
  std::int64_t timedBounces = 0;          ///< points bouncing at a time of impact inside the step
  std::int64_t warmStartedPoints = 0;     ///< points that found last step's impulses by feature id
  std::int64_t islands = 0;               ///< islands of awake dynamic bodies
  std::int64_t velocitySweeps = 0;        ///< Gauss-Seidel velocity sweeps run (see maxVelocityIterations)
  std::int64_t shockSweeps =
      0;  ///< shock propagation's sweeps, over all levels (MethodSettings::shockPropagation)
  std::int64_t solverColours = 0;     ///< colours of the coloured solver (ContactOrder::ByColour)
  std::int64_t overflowPairs = 0;     ///< pairs it solved one by one after the colours
  std::int64_t positionSweeps = 0;    ///< position sweeps run (split impulses, timed bounces' position rows)
  BroadPhaseStats broadPhase = {};    ///< the broad phase's own counters
  NarrowPhaseStats narrowPhase = {};  ///< the narrow phase's own counters
};

}  // namespace talus
